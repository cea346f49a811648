// PNG and JPEG decoded without OpenCV's imgcodecs (io/image_codecs.h) must give exactly what
// cv::imdecode(IMREAD_COLOR) gives: on constructed files of every kind the readers accept, and
// on real photographs of the reference data when it is there.
#include "io/image_codecs.h"

#include <gtest/gtest.h>
#include <spng.h>

#include <filesystem>
#include <fstream>
#include <iostream>
#include <iterator>
#include <map>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <random>
#include <zlib.h>

// jpeglib.h needs size_t and FILE declared first.
#include <jpeglib.h>

#include "io/image_file.h"
#include "io/png_fast.h"
#include "tests/support/temp_dir.h"
#include "util/error.h"

namespace attend {
namespace {

namespace fs = std::filesystem;

// Random samples of `bits` (1, 2, 4, 8 or 16) per sample, packed as PNG rows.
std::vector<uint8_t> PackedRows(int width, int height, int samples_per_pixel, int bits,
                                uint32_t seed) {
  std::mt19937 random(seed);
  const size_t row_bytes = (static_cast<size_t>(width) * samples_per_pixel * bits + 7) / 8;
  std::vector<uint8_t> rows(row_bytes * height);
  if (bits == 16) {
    // Host-endian 16-bit samples (libspng's SPNG_FMT_PNG).
    auto* samples = reinterpret_cast<uint16_t*>(rows.data());
    for (size_t i = 0; i < rows.size() / 2; ++i) samples[i] = static_cast<uint16_t>(random());
  } else {
    for (auto& byte : rows) byte = static_cast<uint8_t>(random());
  }
  return rows;
}

// The PNG that libspng's encoder `ctx` made; frees `ctx`.
std::vector<uchar> TakePng(spng_ctx* ctx) {
  size_t length = 0;
  int error = 0;
  auto* png = static_cast<uchar*>(spng_get_png_buffer(ctx, &length, &error));
  EXPECT_EQ(error, 0);
  std::vector<uchar> bytes(png, png + length);
  free(png);
  spng_ctx_free(ctx);
  return bytes;
}

// A PNG of the given colour type and depth (libspng's encoder), with a palette of 2^bits
// entries for type 3 and, with `transparency`, a tRNS chunk.
std::vector<uchar> MakePng(int width, int height, int colour_type, int bits, bool interlaced,
                           bool transparency, uint32_t seed = 7) {
  const int samples = colour_type == 0 || colour_type == 3 ? 1
                      : colour_type == 4                   ? 2
                      : colour_type == 2                   ? 3
                                                           : 4;
  std::vector<uint8_t> rows = PackedRows(width, height, samples, bits, seed);
  spng_ctx* ctx = spng_ctx_new(SPNG_CTX_ENCODER);
  spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
  spng_ihdr ihdr = {};
  ihdr.width = width;
  ihdr.height = height;
  ihdr.bit_depth = static_cast<uint8_t>(bits);
  ihdr.color_type = static_cast<uint8_t>(colour_type);
  ihdr.interlace_method = interlaced ? 1 : 0;
  EXPECT_EQ(spng_set_ihdr(ctx, &ihdr), 0);
  std::mt19937 random(seed + 1);
  if (colour_type == 3) {
    spng_plte plte = {};
    plte.n_entries = 1u << bits;
    for (uint32_t i = 0; i < plte.n_entries; ++i) {
      plte.entries[i] = {static_cast<uint8_t>(random()), static_cast<uint8_t>(random()),
                         static_cast<uint8_t>(random()), 255};
    }
    EXPECT_EQ(spng_set_plte(ctx, &plte), 0);
  }
  if (transparency) {
    spng_trns trns = {};
    if (colour_type == 3) {
      trns.n_type3_entries = 1u << bits;
      for (uint32_t i = 0; i < trns.n_type3_entries; ++i) {
        trns.type3_alpha[i] = static_cast<uint8_t>(random());
      }
    } else if (colour_type == 0) {
      trns.gray = 1;
    } else {
      trns.red = 1;
      trns.green = 2;
      trns.blue = 3;
    }
    EXPECT_EQ(spng_set_trns(ctx, &trns), 0);
  }
  EXPECT_EQ(spng_encode_image(ctx, rows.data(), rows.size(), SPNG_FMT_PNG, SPNG_ENCODE_FINALIZE),
            0);
  return TakePng(ctx);
}

cv::Mat RandomBgr(int width, int height, uint32_t seed) {
  cv::Mat image(height, width, CV_8UC3);
  cv::RNG rng(seed);
  rng.fill(image, cv::RNG::UNIFORM, 0, 256);
  // Smooth areas too, as in photographs, so that JPEG's chroma upsampling matters.
  cv::rectangle(image, cv::Rect(width / 4, height / 4, width / 2, height / 2),
                cv::Scalar(30, 140, 220), cv::FILLED);
  return image;
}

void ExpectSame(const cv::Mat& ours, const cv::Mat& opencv, const std::string& what) {
  ASSERT_FALSE(opencv.empty()) << what << ": OpenCV cannot decode it";
  ASSERT_FALSE(ours.empty()) << what << ": ours cannot decode it";
  ASSERT_EQ(ours.type(), opencv.type()) << what;
  ASSERT_EQ(ours.size(), opencv.size()) << what;
  EXPECT_EQ(cv::norm(ours, opencv, cv::NORM_INF), 0.0) << what;
}

TEST(ImageCodecs, PngOfEveryColourTypeAndDepthDecodesAsOpenCv) {
  struct Kind {
    int colour_type;
    std::vector<int> depths;
  };
  const std::vector<Kind> kinds = {{0, {1, 2, 4, 8, 16}}, {2, {8, 16}}, {3, {1, 2, 4, 8}},
                                   {4, {8, 16}},          {6, {8, 16}}};
  int checked = 0;
  for (const Kind& kind : kinds) {
    for (int bits : kind.depths) {
      for (bool interlaced : {false, true}) {
        for (bool transparency : {false, true}) {
          if (transparency && (kind.colour_type == 4 || kind.colour_type == 6)) continue;
          const std::vector<uchar> png =
              MakePng(37, 23, kind.colour_type, bits, interlaced, transparency);
          const std::string what = "colour type " + std::to_string(kind.colour_type) + ", " +
                                   std::to_string(bits) + " bits" +
                                   (interlaced ? ", interlaced" : "") +
                                   (transparency ? ", tRNS" : "");
          ExpectSame(DecodePngColour(png), cv::imdecode(png, cv::IMREAD_COLOR), what);
          ++checked;
        }
      }
    }
  }
  EXPECT_EQ(checked, 52);
}

TEST(ImageCodecs, PngWrittenByOpenCvDecodesAsOpenCv) {
  const cv::Mat bgr = RandomBgr(64, 48, 1);
  cv::Mat grey, bgra, bgr16, grey16;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  bgr.convertTo(bgr16, CV_16U, 257.0, 3.0);
  grey.convertTo(grey16, CV_16U, 251.0, 5.0);
  for (const cv::Mat& image : {bgr, grey, bgra, bgr16, grey16}) {
    std::vector<uchar> png;
    ASSERT_TRUE(cv::imencode(".png", image, png));
    ExpectSame(DecodePngColour(png), cv::imdecode(png, cv::IMREAD_COLOR),
               "OpenCV's PNG of type " + std::to_string(image.type()));
  }
}

TEST(ImageCodecs, OurPngEncodingDecodesToTheSamePixels) {
  const cv::Mat bgr = RandomBgr(41, 29, 2);
  cv::Mat grey, bgra, grey16;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  bgra.forEach<cv::Vec4b>([](cv::Vec4b& p, const int* at) { p[3] = static_cast<uchar>(at[1]); });
  grey.convertTo(grey16, CV_16U, 257.0, 1.0);
  for (const cv::Mat& image : {bgr, grey, bgra, grey16}) {
    for (int level : {0, 1, 9}) {
      std::vector<uchar> png;
      ASSERT_TRUE(EncodePng(image, level, &png));
      const cv::Mat back = cv::imdecode(png, cv::IMREAD_UNCHANGED);
      ASSERT_EQ(back.type(), image.type());
      EXPECT_EQ(cv::norm(back, image, cv::NORM_INF), 0.0) << "type " << image.type();
    }
  }
  // A part of a larger image (rows not packed) too.
  std::vector<uchar> png;
  ASSERT_TRUE(EncodePng(bgr(cv::Rect(3, 4, 20, 10)), 1, &png));
  EXPECT_EQ(cv::norm(cv::imdecode(png, cv::IMREAD_UNCHANGED), bgr(cv::Rect(3, 4, 20, 10)),
                     cv::NORM_INF),
            0.0);
  std::vector<uchar> none;
  EXPECT_FALSE(EncodePng(cv::Mat(4, 4, CV_32FC1), 1, &none));
}

// A PNG of `image` (8-bit grey, BGR or BGRA) with every row filtered with `filter` (one of
// libspng's SPNG_FILTER_CHOICE_ values).
std::vector<uchar> PngWithFilter(const cv::Mat& image, int filter) {
  cv::Mat rows;
  if (image.channels() == 3) {
    cv::cvtColor(image, rows, cv::COLOR_BGR2RGB);
  } else if (image.channels() == 4) {
    cv::cvtColor(image, rows, cv::COLOR_BGRA2RGBA);
  } else {
    rows = image.clone();
  }
  spng_ctx* ctx = spng_ctx_new(SPNG_CTX_ENCODER);
  spng_set_option(ctx, SPNG_ENCODE_TO_BUFFER, 1);
  spng_set_option(ctx, SPNG_FILTER_CHOICE, filter);
  spng_ihdr ihdr = {};
  ihdr.width = static_cast<uint32_t>(image.cols);
  ihdr.height = static_cast<uint32_t>(image.rows);
  ihdr.bit_depth = 8;
  ihdr.color_type = static_cast<uint8_t>(image.channels() == 1 ? 0 : image.channels() == 3 ? 2 : 6);
  EXPECT_EQ(spng_set_ihdr(ctx, &ihdr), 0);
  EXPECT_EQ(spng_encode_image(ctx, rows.data, rows.total() * rows.elemSize(), SPNG_FMT_PNG,
                              SPNG_ENCODE_FINALIZE),
            0);
  return TakePng(ctx);
}

TEST(ImageCodecs, FastPngPathUndoesEveryFilterAsOpenCv) {
  // Noise with flat areas and edges, so that each of Paeth's three choices is taken.
  const cv::Mat bgr = RandomBgr(67, 31, 5);
  cv::Mat grey, bgra;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  cv::cvtColor(bgr, bgra, cv::COLOR_BGR2BGRA);
  bgra.forEach<cv::Vec4b>([](cv::Vec4b& p, const int* at) { p[3] = static_cast<uchar>(7 * at[1]); });
  const std::vector<std::pair<int, std::string>> filters = {
      {SPNG_FILTER_CHOICE_NONE, "None"},   {SPNG_FILTER_CHOICE_SUB, "Sub"},
      {SPNG_FILTER_CHOICE_UP, "Up"},       {SPNG_FILTER_CHOICE_AVG, "Average"},
      {SPNG_FILTER_CHOICE_PAETH, "Paeth"}, {SPNG_FILTER_CHOICE_ALL, "adaptive"}};
  int checked = 0;
  for (const cv::Mat& image : {grey, bgr, bgra}) {
    for (const auto& [filter, name] : filters) {
      const std::vector<uchar> png = PngWithFilter(image, filter);
      const std::string what = std::to_string(image.channels()) + " channels, " + name;
      const cv::Mat opencv = cv::imdecode(png, cv::IMREAD_COLOR);
      for (bool portable : {false, true}) {
        UsePortablePngFilters(portable);
        cv::Mat fast;
        const bool taken = DecodeCommonPng(png, &fast);
        UsePortablePngFilters(false);
        ASSERT_TRUE(taken) << what << ": the fast path declined a common PNG";
        ExpectSame(fast, opencv, what + (portable ? ", portable filters" : ""));
        ++checked;
      }
      ExpectSame(DecodePngColour(png), opencv, what + ", DecodePngColour");
    }
  }
  EXPECT_EQ(checked, 36);
}

// A PNG of 8-bit RGB `rows` (each a filter byte and the filtered pixels), built chunk by chunk.
std::vector<uchar> PngOfRows(int width, int height, const std::vector<uchar>& rows) {
  std::vector<uchar> png = {0x89, 'P', 'N', 'G', '\r', '\n', 0x1A, '\n'};
  auto put32 = [&png](uint32_t v) {
    for (int k = 0; k < 4; ++k) png.push_back(static_cast<uchar>(v >> (24 - 8 * k)));
  };
  auto chunk = [&](const char* type, const std::vector<uchar>& body) {
    put32(static_cast<uint32_t>(body.size()));
    const size_t start = png.size();
    png.insert(png.end(), type, type + 4);
    png.insert(png.end(), body.begin(), body.end());
    put32(static_cast<uint32_t>(crc32(0L, png.data() + start, static_cast<uInt>(png.size() - start))));
  };
  std::vector<uchar> header = {0, 0, 0, static_cast<uchar>(width), 0, 0, 0,
                               static_cast<uchar>(height), 8, 2, 0, 0, 0};
  chunk("IHDR", header);
  uLongf size = compressBound(rows.size());
  std::vector<uchar> data(size);
  EXPECT_EQ(compress(data.data(), &size, rows.data(), rows.size()), Z_OK);
  data.resize(size);
  chunk("IDAT", data);
  chunk("IEND", {});
  return png;
}

TEST(ImageCodecs, FastPngPathLeavesOtherKindsAndDamageToTheCompleteDecoder) {
  cv::Mat out;
  // 16 bits, a palette, grey with alpha, interlacing: declined, yet decoded by DecodePngColour.
  for (const std::vector<uchar>& png :
       {MakePng(9, 7, 2, 16, false, false), MakePng(9, 7, 3, 8, false, false),
        MakePng(9, 7, 4, 8, false, false), MakePng(9, 7, 2, 8, true, false)}) {
    EXPECT_FALSE(DecodeCommonPng(png, &out));
    ExpectSame(DecodePngColour(png), cv::imdecode(png, cv::IMREAD_COLOR), "a declined kind");
  }
  const std::vector<uchar> good = PngWithFilter(RandomBgr(20, 10, 9), SPNG_FILTER_CHOICE_ALL);
  ASSERT_TRUE(DecodeCommonPng(good, &out));
  // A flipped bit in the image data: its chunk's CRC no longer matches.
  std::vector<uchar> damaged = good;
  damaged[damaged.size() - 30] ^= 0x10;
  EXPECT_FALSE(DecodeCommonPng(damaged, &out));
  // Cut short: no IEND.
  EXPECT_FALSE(DecodeCommonPng(std::vector<uchar>(good.begin(), good.end() - 12), &out));
  // Well-formed chunks and zlib stream, but a row's filter type out of range (9).
  std::vector<uchar> rows(3 * (1 + 4 * 3), 50);
  rows[0] = 0;
  rows[13] = 9;
  rows[26] = 1;
  EXPECT_FALSE(DecodeCommonPng(PngOfRows(4, 3, rows), &out));
  rows[13] = 4;
  ASSERT_TRUE(DecodeCommonPng(PngOfRows(4, 3, rows), &out));
  EXPECT_EQ(out.at<cv::Vec3b>(2, 3), cv::Vec3b(200, 200, 200));  // Sub: 4 x 50
}

// A JPEG with an EXIF block of orientation `orientation` right after its start marker.
std::vector<uchar> WithExifOrientation(const std::vector<uchar>& jpeg, int orientation,
                                       bool big_endian) {
  std::vector<uchar> tiff = big_endian ? std::vector<uchar>{'M', 'M', 0, 42, 0, 0, 0, 8}
                                       : std::vector<uchar>{'I', 'I', 42, 0, 8, 0, 0, 0};
  auto put16 = [&](int v) {
    if (big_endian) {
      tiff.push_back(static_cast<uchar>(v >> 8));
      tiff.push_back(static_cast<uchar>(v));
    } else {
      tiff.push_back(static_cast<uchar>(v));
      tiff.push_back(static_cast<uchar>(v >> 8));
    }
  };
  put16(1);       // one entry
  put16(0x0112);  // Orientation
  put16(3);       // SHORT
  put16(0);
  put16(1);  // count 1
  put16(orientation);
  put16(0);
  put16(0);
  put16(0);
  put16(0);  // no next IFD
  std::vector<uchar> app1 = {'E', 'x', 'i', 'f', 0, 0};
  app1.insert(app1.end(), tiff.begin(), tiff.end());
  const size_t length = app1.size() + 2;
  std::vector<uchar> out(jpeg.begin(), jpeg.begin() + 2);
  out.insert(out.end(), {0xFF, 0xE1, static_cast<uchar>(length >> 8), static_cast<uchar>(length)});
  out.insert(out.end(), app1.begin(), app1.end());
  out.insert(out.end(), jpeg.begin() + 2, jpeg.end());
  return out;
}

TEST(ImageCodecs, JpegOfEveryKindDecodesAsOpenCv) {
  const cv::Mat bgr = RandomBgr(53, 37, 3);
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  const std::vector<std::pair<std::string, std::vector<int>>> settings = {
      {"default", {}},
      {"quality 100", {cv::IMWRITE_JPEG_QUALITY, 100}},
      {"quality 20", {cv::IMWRITE_JPEG_QUALITY, 20}},
      {"progressive", {cv::IMWRITE_JPEG_PROGRESSIVE, 1}},
      {"optimised", {cv::IMWRITE_JPEG_OPTIMIZE, 1}},
      {"restart intervals", {cv::IMWRITE_JPEG_RST_INTERVAL, 2}},
  };
  for (const auto& [name, params] : settings) {
    for (const cv::Mat& image : {bgr, grey}) {
      std::vector<uchar> jpeg;
      ASSERT_TRUE(cv::imencode(".jpg", image, jpeg, params));
      const std::string what = name + (image.channels() == 1 ? ", grey" : ", colour");
      ExpectSame(DecodeJpegColour(jpeg), cv::imdecode(jpeg, cv::IMREAD_COLOR), what);
    }
  }
}

// A JPEG written by libjpeg with the first component sampled `h` x `v` times the others (2x2
// is OpenCV's 4:2:0), or a four-component CMYK one.
std::vector<uchar> LibjpegFile(const cv::Mat& bgr, int h, int v, bool cmyk) {
  jpeg_compress_struct info;
  jpeg_error_mgr errors;
  info.err = jpeg_std_error(&errors);
  jpeg_create_compress(&info);
  unsigned char* buffer = nullptr;
  unsigned long size = 0;
  jpeg_mem_dest(&info, &buffer, &size);
  info.image_width = bgr.cols;
  info.image_height = bgr.rows;
  info.input_components = cmyk ? 4 : 3;
  info.in_color_space = cmyk ? JCS_CMYK : JCS_EXT_BGR;
  jpeg_set_defaults(&info);
  if (!cmyk) {
    info.comp_info[0].h_samp_factor = h;
    info.comp_info[0].v_samp_factor = v;
  }
  jpeg_start_compress(&info, TRUE);
  cv::Mat rows = bgr;
  if (cmyk) {
    cv::cvtColor(bgr, rows, cv::COLOR_BGR2BGRA);  // any four bytes a pixel will do
  }
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = rows.ptr<uchar>(static_cast<int>(info.next_scanline));
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  std::vector<uchar> bytes(buffer, buffer + size);
  free(buffer);
  return bytes;
}

TEST(ImageCodecs, JpegOfEverySamplingDecodesAsOpenCv) {
  const cv::Mat bgr = RandomBgr(53, 37, 11);
  for (const auto& [h, v] : std::vector<std::pair<int, int>>{{1, 1}, {2, 1}, {1, 2}, {2, 2}, {4, 1}}) {
    const std::vector<uchar> jpeg = LibjpegFile(bgr, h, v, false);
    ExpectSame(DecodeJpegColour(jpeg), cv::imdecode(jpeg, cv::IMREAD_COLOR),
               "sampling " + std::to_string(h) + "x" + std::to_string(v));
  }
  // CMYK is left to OpenCV (its own conversion), which ReadImageFile then asks.
  const std::vector<uchar> cmyk = LibjpegFile(bgr, 1, 1, true);
  EXPECT_TRUE(DecodeJpegColour(cmyk).empty());
  ExpectSame(DecodeImage(cmyk, cv::IMREAD_COLOR, "cmyk"), cv::imdecode(cmyk, cv::IMREAD_COLOR),
             "CMYK through DecodeImage");
}

TEST(ImageCodecs, JpegExifOrientationIsAppliedAsOpenCv) {
  const cv::Mat bgr = RandomBgr(31, 17, 4);
  std::vector<uchar> jpeg;
  ASSERT_TRUE(cv::imencode(".jpg", bgr, jpeg));
  for (bool big_endian : {false, true}) {
    for (int orientation = 1; orientation <= 8; ++orientation) {
      const std::vector<uchar> turned = WithExifOrientation(jpeg, orientation, big_endian);
      const cv::Mat ours = DecodeJpegColour(turned);
      ExpectSame(ours, cv::imdecode(turned, cv::IMREAD_COLOR),
                 "orientation " + std::to_string(orientation));
      // Orientations 5 to 8 swap width and height: the EXIF block was read.
      EXPECT_EQ(ours.cols, orientation >= 5 ? 17 : 31);
    }
  }
}

TEST(ImageCodecs, DecodersDeclineWhatTheyDoNotRead) {
  // Empty answers send ReadImageFile to OpenCV, whose answer is then the reference.
  const std::vector<uchar> empty_jpeg = {0xFF, 0xD8, 0xFF, 0xD9};
  EXPECT_TRUE(DecodeJpegColour(empty_jpeg).empty());
  EXPECT_TRUE(DecodePngColour(empty_jpeg).empty());
  std::vector<uchar> png = MakePng(8, 8, 2, 8, false, false);
  png[20] ^= 0x55;  // the IHDR's CRC no longer matches
  EXPECT_TRUE(DecodePngColour(png).empty());
}

TEST(ImageCodecs, ExifOrientationReadsOnlyAWellFormedBlock) {
  const uchar little[] = {'I', 'I', 42, 0, 8, 0, 0, 0, 1, 0, 0x12, 0x01, 3, 0, 1, 0, 0, 0, 6, 0, 0, 0};
  EXPECT_EQ(ExifOrientation(little, sizeof(little)), 6);
  EXPECT_EQ(ExifOrientation(little, 12), 0);  // cut short inside the entry
  const uchar wrong[] = {'I', 'I', 43, 0, 8, 0, 0, 0, 1, 0, 0x12, 0x01, 3, 0, 1, 0, 0, 0, 6, 0, 0, 0};
  EXPECT_EQ(ExifOrientation(wrong, sizeof(wrong)), 0);
  const uchar nine[] = {'M', 'M', 0, 42, 0, 0, 0, 8, 0, 1, 0x01, 0x12, 0, 3, 0, 0, 0, 1, 0, 9, 0, 0};
  EXPECT_EQ(ExifOrientation(nine, sizeof(nine)), 0);
}

std::vector<uchar> FileBytes(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::vector<uchar>((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

TEST(ImageCodecs, ReadImageFileGivesOpenCvsPixelsAndRefusesCutFiles) {
  testing::TempDir dir;
  const cv::Mat bgr = RandomBgr(40, 30, 5);
  for (const std::string extension : {".png", ".jpg", ".bmp", ".ppm"}) {
    const std::string path = (fs::path(dir.path()) / ("image" + extension)).string();
    ASSERT_TRUE(cv::imwrite(path, bgr));
    ExpectSame(ReadImageFile(path, cv::IMREAD_COLOR, path), cv::imread(path, cv::IMREAD_COLOR),
               extension);
    ExpectSame(ReadImageFile(path, cv::IMREAD_GRAYSCALE, path),
               cv::imread(path, cv::IMREAD_GRAYSCALE), extension + " grey");
    if (extension == ".png" || extension == ".jpg") {
      std::vector<uchar> bytes = FileBytes(path);
      bytes.resize(bytes.size() * 2 / 3);
      const std::string cut = (fs::path(dir.path()) / ("cut" + extension)).string();
      std::ofstream(cut, std::ios::binary)
          .write(reinterpret_cast<const char*>(bytes.data()), static_cast<std::streamsize>(bytes.size()));
      try {
        ReadImageFile(cut, cv::IMREAD_COLOR, cut);
        ADD_FAILURE() << cut << " was read";
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("cut short"), std::string::npos) << e.what();
      }
    }
  }
}

TEST(ImageCodecs, WriteImageWritesWhatOpenCvReadsBack) {
  testing::TempDir dir;
  const cv::Mat bgr = RandomBgr(40, 30, 6);
  for (const std::string extension : {".png", ".bmp", ".jpg"}) {
    const std::string path = (fs::path(dir.path()) / ("w" + extension)).string();
    ASSERT_TRUE(WriteImage(path, bgr));
    const cv::Mat back = cv::imread(path, cv::IMREAD_COLOR);
    ASSERT_FALSE(back.empty()) << extension;
    if (extension != ".jpg") {
      EXPECT_EQ(cv::norm(back, bgr, cv::NORM_INF), 0.0) << extension;
    }
  }
  std::vector<uchar> png;
  ASSERT_TRUE(EncodeImage(".png", bgr, &png));
  EXPECT_EQ(cv::norm(cv::imdecode(png, cv::IMREAD_COLOR), bgr, cv::NORM_INF), 0.0);
}

// Real photographs and frames of the reference data beside the repository, when it is there.
TEST(ImageCodecs, RealPhotographsDecodeAsOpenCv) {
  const fs::path data = fs::path(ATTEND_SOURCE_ROOT) / ".." / "shared" / "data";
  std::error_code error;
  if (!fs::is_directory(data, error)) GTEST_SKIP() << data << " is absent";
  int checked = 0;
  std::map<std::string, int> per_folder;
  for (auto it = fs::recursive_directory_iterator(data, error);
       it != fs::recursive_directory_iterator() && checked < 60; it.increment(error)) {
    if (error) break;
    if (!it->is_regular_file(error)) continue;
    const std::string extension = it->path().extension().string();
    if (extension != ".png" && extension != ".jpg" && extension != ".jpeg") continue;
    // A few files of each folder, so that every dataset is seen.
    if (++per_folder[it->path().parent_path().string()] > 2) continue;
    const std::vector<uchar> bytes = FileBytes(it->path());
    const cv::Mat opencv = cv::imdecode(bytes, cv::IMREAD_COLOR);
    if (opencv.empty()) continue;
    const cv::Mat ours = extension == ".png" ? DecodePngColour(bytes) : DecodeJpegColour(bytes);
    ExpectSame(ours, opencv, it->path().string());
    ++checked;
  }
  if (checked == 0) GTEST_SKIP() << "no PNG or JPEG file under " << data;
  std::cout << checked << " files of " << per_folder.size() << " folders compared\n";
}

}  // namespace
}  // namespace attend
