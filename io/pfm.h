// Portable float map (PFM) reading and writing. Float maps are PFM throughout attend:
// disparity maps, saliency, inhibition and feature dumps.
#pragma once

#include <opencv2/core.hpp>
#include <string>

namespace attend {

// Reads a one-channel ("Pf") or three-channel ("PF") PFM file of either byte order into a
// CV_32FC1 / CV_32FC3 matrix, top row first. Infinities (Middlebury's "unknown") are kept.
// Throws InputError naming the file on any problem.
cv::Mat ReadPfm(const std::string& path);

// ReadPfm for a map that must have one channel (a disparity, saliency or inhibition map);
// `what` names it in the error for a three-channel file.
cv::Mat ReadPfmOneChannel(const std::string& path, const std::string& what);

// Writes a CV_32FC1 or CV_32FC3 matrix as little-endian PFM (bottom row first, as the format
// requires). Throws InputError naming the file when it cannot be written.
void WritePfm(const std::string& path, const cv::Mat& map);

}  // namespace attend
