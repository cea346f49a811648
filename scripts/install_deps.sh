#!/usr/bin/env bash
# Installs the Debian 12 packages attend needs, only those that are missing. Idempotent: when
# everything is present it changes nothing and takes a moment.
set -euo pipefail

packages=(
  g++ make cmake pkg-config
  libopencv-dev libopencv-contrib-dev libeigen3-dev libyaml-cpp-dev
  libcli11-dev nlohmann-json3-dev libgtest-dev libgmock-dev libbenchmark-dev
  libjs-chart.js  # the charts of attend compare's report, inlined (docs/COMPARE.md)
  chromium        # renders the report in its test (tests/cli/compare_cli_test.cc)
  opencv-data     # the cascade models of the faces channel (features/detectors.h)
  opencv-doc      # its chessboard stereo pairs (left01.jpg...): the test of attend calibrate
  libspng-dev libjpeg62-turbo-dev  # PNG and JPEG without OpenCV's imgcodecs (io/image_codecs.h)
  libdeflate-dev  # the image data of common PNG frames, twice as fast as zlib (io/png_fast.h)
  # the Python module attend (python/, docs/PYTHON.md), its tests and its example
  pybind11-dev python3-dev python3-numpy python3-pytest python3-pandas python3-matplotlib
  python3-onnx    # builds the small ONNX network of the dnn backend's test (tests/features)
  python3-scipy   # scipy.io reads the MATLAB files of scripts/convert_fixations.py and its tests
  # attend sweep --slurm and the one-node cluster its tests start (scripts/slurm_local.sh)
  slurm-wlm munge
  # live input through OpenCV's GStreamer backend and its tests' videotestsrc pipelines
  gstreamer1.0-plugins-base gstreamer1.0-plugins-good gstreamer1.0-tools
  universal-ctags # where functions begin and end, for scripts/check_structure.py's test
  ccache          # the builds reuse what earlier builds on the machine compiled (scripts/ccache.sh)
  curl            # scripts/get_models.sh fetches the dnn models with it (docs/MODELS.md) and its test
)

missing=()
for package in "${packages[@]}"; do
  if ! dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed"; then
    missing+=("$package")
  fi
done

if [ ${#missing[@]} -eq 0 ]; then
  echo "[attend] all packages present"
  exit 0
fi

sudo=""
if [ "$(id -u)" -ne 0 ]; then
  if command -v sudo >/dev/null 2>&1; then
    sudo="sudo"
  else
    echo "[attend] error: missing packages (${missing[*]}) and not root; run as root" >&2
    exit 1
  fi
fi

echo "[attend] installing: ${missing[*]}"
export DEBIAN_FRONTEND=noninteractive
$sudo apt-get update -qq
$sudo apt-get install -y -qq --no-install-recommends "${missing[@]}"
