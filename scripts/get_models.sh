#!/usr/bin/env bash
# Downloads the pretrained models of attend's dnn backend (docs/MODELS.md) from their upstream
# repositories into a folder, and checks each file against the sha256 sum pinned below.
#
#   scripts/get_models.sh [--only NAME] DIR
#   scripts/get_models.sh --list [--only NAME]
#
# DIR gets one sub-folder a model family: yolo_fastest/, yolox/, osnet/, yunet/ (NAME is one of
# those). A file already in DIR with the pinned sum is kept; any other is downloaded to a
# temporary name beside its place, checked, and only then moved into place. A download whose
# sum differs is deleted, and the file, the expected and the got sum are printed. --list prints
# each file's pinned sum, place and URL and downloads nothing.
#
# ATTEND_MODELS_BASE_URL, when set, replaces each file's upstream URL by
# BASE_URL/SUBFOLDER/FILE, the layout DIR itself has (e.g. BASE_URL/yolox/yolox_nano.onnx): a
# mirror, or a file:// copy of a models folder as its test uses (tests/scripts/).
#
# Uses curl (wget when curl is absent; file:// URLs need curl). Exit 0 when every file is present
# and verified, 1 when a download failed or a sum differed, 2 on a usage error.
set -euo pipefail

usage() {
  sed -n '2,/^set -euo/{/^set -euo/d;s/^# \{0,1\}//;p}' "${BASH_SOURCE[0]}"
}

# The pinned files: SUBFOLDER FILE SHA256 UPSTREAM (OWNER/REPO/COMMIT/PATH on
# raw.githubusercontent.com). The sums pin the files whatever the commit names. Yolo-Fastest's
# data/coco.names and LICENSE are where its parent, Darknet, keeps them (docs/MODELS.md).
readonly FILES=(
  "yolo_fastest yolo-fastest-1.1_body.cfg 045b8e276ebe3924474da8c866b7e709159ea067137b5d66bf9dd560411b2c1a dog-qiuqiu/Yolo-Fastest/96a2900d/ModelZoo/yolo-fastest-1.1_body/yolo-fastest-1.1_body.cfg"
  "yolo_fastest yolo-fastest-1.1_body.weights 5bbb6d878f6e2eb3deee39e91dc6f9b39700e99ec83fa94d258670a554949728 dog-qiuqiu/Yolo-Fastest/96a2900d/ModelZoo/yolo-fastest-1.1_body/yolo-fastest-1.1_body.weights"
  "yolo_fastest yolo-fastest-1.1.cfg f6df5775c1e862998cf69046eba9265be3ae84dfe8b2caab7529823f0795bf70 dog-qiuqiu/Yolo-Fastest/96a2900d/ModelZoo/yolo-fastest-1.1_coco/yolo-fastest-1.1.cfg"
  "yolo_fastest yolo-fastest-1.1.weights 1c445c42bbd6df63edea2cc69f99667b5650d663ca11e34b116240740cd42890 dog-qiuqiu/Yolo-Fastest/96a2900d/ModelZoo/yolo-fastest-1.1_coco/yolo-fastest-1.1.weights"
  "yolo_fastest coco.names 634a1132eb33f8091d60f2c346ababe8b905ae08387037aed883953b7329af84 dog-qiuqiu/Yolo-Fastest/96a2900d/data/coco.names"
  "yolo_fastest LICENSE 2021f0b8d6426fbf9a2f0126f1e8a7d3b1d7027c871b9979fa2543b9557000c4 dog-qiuqiu/Yolo-Fastest/96a2900d/LICENSE"
  "yolox yolox_nano.onnx e8af074932d4ed7e232278e3055cefcdea3edf178874a3694ae292649fb464dd Bigisland1729/object-detection-models/7f3f2fa3/yolox_nano.onnx"
  "osnet osnet_x0_25_msmt17.onnx 61b2604171ef9d58d21758626f83b35a253c3d7123976523a6e03068c3c95d7b akshaydhame2001/YOLOv8_Tracking_TensorRT/cb948b32/osnet_x0_25_msmt17.onnx"
  "yunet yunet_n_640_640.onnx 25a606a145a5b6d7271ae138fbd00eba91dad8b83222ae3f2c7ecd0f4a7b0e31 ShiqiYu/libfacedetection.train/0047ac24/onnx/yunet_n_640_640.onnx"
  "yunet LICENSE d096f0e4f790316e1df89675682a51c68ca64745a611689ccd37bd246835440e ShiqiYu/libfacedetection.train/0047ac24/LICENSE"
)
readonly NAMES=(yolo_fastest yolox osnet yunet)

usage_error() {
  echo "get_models.sh: $1" >&2
  echo "usage: scripts/get_models.sh [--only NAME] DIR | --list [--only NAME]  (-h for help)" >&2
  exit 2
}

only="" list=false dir="" positional=()
while [[ $# -gt 0 ]]; do
  case "$1" in
    -h | --help) usage; exit 0 ;;
    --list) list=true; shift ;;
    --only)
      [[ $# -ge 2 ]] || usage_error "--only needs a NAME (${NAMES[*]})"
      only="$2"; shift 2 ;;
    --only=*) only="${1#--only=}"; shift ;;
    --) shift; positional+=("$@"); break ;;
    -?*) usage_error "unknown option '$1'" ;;
    *) positional+=("$1"); shift ;;
  esac
done
[[ ${#positional[@]} -le 1 ]] || usage_error "one DIR only, got ${#positional[@]}: ${positional[*]}"
[[ ${#positional[@]} -eq 0 ]] || dir="${positional[0]}"
if [[ -n "$only" && " ${NAMES[*]} " != *" $only "* ]]; then
  usage_error "--only '$only': not one of ${NAMES[*]}"
fi
if ! $list && [[ -z "$dir" ]]; then
  usage_error "no DIR given"
fi

base_url="${ATTEND_MODELS_BASE_URL:-}"
base_url="${base_url%/}"
# url SUBFOLDER FILE UPSTREAM: where a file is fetched from.
url() {
  if [[ -n "$base_url" ]]; then
    echo "$base_url/$1/$2"
  else
    echo "https://raw.githubusercontent.com/$3"
  fi
}

if $list; then
  for entry in "${FILES[@]}"; do
    read -r sub name sum upstream <<<"$entry"
    [[ -z "$only" || "$only" == "$sub" ]] || continue
    echo "$sum  $sub/$name  $(url "$sub" "$name" "$upstream")"
  done
  exit 0
fi

if command -v curl >/dev/null 2>&1; then
  fetch() { curl --fail --silent --show-error --location --retry 2 --connect-timeout 30 -o "$2" "$1"; }
elif command -v wget >/dev/null 2>&1; then
  fetch() { wget --quiet --tries=3 --timeout=30 -O "$2" "$1"; }
else
  echo "get_models.sh: neither curl nor wget is installed (scripts/install_deps.sh installs curl)" >&2
  exit 1
fi
if command -v sha256sum >/dev/null 2>&1; then
  sha256() { sha256sum "$1" | cut -d' ' -f1; }
elif command -v shasum >/dev/null 2>&1; then
  sha256() { shasum -a 256 "$1" | cut -d' ' -f1; }
else
  echo "get_models.sh: neither sha256sum nor shasum is installed" >&2
  exit 1
fi

# The download in progress and the folders this run made, removed if the run is cut short or
# leaves them empty.
part=""
made_dirs=()
cleanup() {
  [[ -z "$part" ]] || rm -f -- "$part"
  local d
  for d in "${made_dirs[@]}"; do rmdir -- "$d" 2>/dev/null || true; done
}
trap cleanup EXIT
trap 'exit 1' INT TERM HUP

if [[ ! -d "$dir" ]]; then
  mkdir -p -- "$dir"
  made_dirs+=("$dir")
fi

# stale_note TARGET: says that a file already in place with another sum was left as it was.
stale_note() {
  if [[ -f "$1" ]]; then
    echo "  the file already at $1 (another sum) was left as it was" >&2
  fi
}

failed=0 total=0 fetched=0
for entry in "${FILES[@]}"; do
  read -r sub name want upstream <<<"$entry"
  [[ -z "$only" || "$only" == "$sub" ]] || continue
  total=$((total + 1))
  target="$dir/$sub/$name"
  if [[ -f "$target" ]]; then
    got="$(sha256 "$target")"
    if [[ "$got" == "$want" ]]; then
      echo "[get_models] $sub/$name: present, sum verified"
      continue
    fi
    echo "[get_models] $sub/$name: present with another sum ($got); downloading it again"
  fi
  if [[ ! -d "$dir/$sub" ]]; then
    mkdir -p -- "$dir/$sub"
    made_dirs=("$dir/$sub" "${made_dirs[@]}")
  fi
  source_url="$(url "$sub" "$name" "$upstream")"
  echo "[get_models] $sub/$name: downloading $source_url"
  part="$(mktemp "$dir/$sub/.$name.part.XXXXXX")"
  if ! fetch "$source_url" "$part"; then
    rm -f -- "$part"; part=""
    echo "[get_models] error: $sub/$name: download failed from $source_url" >&2
    stale_note "$target"
    failed=$((failed + 1))
    continue
  fi
  got="$(sha256 "$part")"
  if [[ "$got" != "$want" ]]; then
    rm -f -- "$part"; part=""
    echo "[get_models] error: $sub/$name: sha256 differs, download deleted" >&2
    echo "  file:     $sub/$name (from $source_url)" >&2
    echo "  expected: $want" >&2
    echo "  got:      $got" >&2
    stale_note "$target"
    failed=$((failed + 1))
    continue
  fi
  chmod 0644 -- "$part"
  mv -f -- "$part" "$target"
  part=""
  fetched=$((fetched + 1))
done

if [[ $failed -gt 0 ]]; then
  echo "[get_models] $failed of $total files failed; no download that failed was kept in $dir" >&2
  exit 1
fi
echo "[get_models] all $total files present and verified in $dir ($fetched downloaded)"
