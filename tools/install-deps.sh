#!/usr/bin/env bash
# Installs the Debian packages mosb needs, when any is missing. Usage: tools/install-deps.sh
# [build|all]. `build` (tools/quickstart.sh): what building the program and its main job need;
# `all` (the default; tests/run-all.sh): that and what the tests, the lint and the fuzzers add.
set -euo pipefail
what="${1:-all}"
build=(
  g++ cmake ninja-build pkg-config          # toolchain
  libxxhash-dev                             # XXH3 checksums and digests
  libcli11-dev                              # the mosb command line
  nlohmann-json3-dev                        # JSON: --json output, solver logs, manifests
  libtomlplusplus-dev                       # TOML: solver profiles and experiment files
  libssl-dev                                # SHA-256 (libcrypto) for manifests and stores
  libcurl4-openssl-dev                      # HTTP(S) transfers of mosb store pull (mosb::pull)
  libexpat1-dev                             # streaming XML parser: GraphML roadmaps
  zlib1g-dev libbz2-dev liblzma-dev libzstd-dev  # compressed inputs
  librsvg2-dev libcairo2-dev                # mosb plot -o fig.pdf|fig.png (the program only)
  doctest-dev                               # unit tests (the release preset configures them)
)
tests=(
  nginx-light                               # the web server the store pull tests publish with
  gzip bzip2 xz-utils zstd                  # compressed test fixtures
  python3 python3-numpy python3-xxhash      # the reference reader and the CLI tests
  python3-dev python3-pybind11 pybind11-dev python3-setuptools python3-pip python3-venv  # python/
  python3-scipy python3-pandas python3-networkx python3-igraph  # python/'s adapters (optional)
  clang libclang-rt-14-dev                  # libFuzzer
  chromium                                  # renders mosb plot's SVG and mosb report in their tests
  slurm-wlm munge                           # a one-node SLURM cluster (tools/slurm-cluster.sh) for mosb run --slurm's test
  poppler-utils                             # pdfinfo, pdftotext: the PDF figures' tests
  groff-base                                # groff: the generated man page renders without warnings
  texlive-latex-base texlive-latex-recommended  # pdflatex and booktabs: the report's .tex tables compile
  python3-matplotlib                        # mosb.plot (python/), optional
  clang-format clang-tidy                   # style and static checks (tools/lint.sh)
)
case "$what" in
  build) packages=("${build[@]}") ;;
  all) packages=("${build[@]}" "${tests[@]}") ;;
  *) echo "usage: tools/install-deps.sh [build|all]" >&2; exit 2 ;;
esac
missing=()
for package in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$package" 2>/dev/null | grep -q "install ok installed" || missing+=("$package")
done
if ((${#missing[@]} > 0)); then
  sudo=""
  if [[ $(id -u) -ne 0 ]]; then sudo="sudo"; fi
  echo "mosb: installing ${missing[*]}"
  $sudo apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $sudo apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
