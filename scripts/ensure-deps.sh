#!/usr/bin/env bash
# Installs the system libraries stochvib needs when they are missing (Debian/Ubuntu):
#   libhdf5-dev + pkg-config (always), python3 + h5py (with --with-h5py, for the file-layout tests),
#   chromium-headless-shell + poppler-utils + python3 html5lib (with --with-browser, for the test that opens
#   the HTML report in a real browser, prints it to PDF and validates it: tests/suite/report_browser.rs).
# Uses sudo only when not root. Does nothing when everything is present.
set -euo pipefail
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
apt_updated=0
apt_install() {
  if [ "$apt_updated" -eq 0 ]; then $SUDO apt-get update -qq; apt_updated=1; fi
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "$@" >/dev/null
}
# python_module MODULE PIP-NAME DEBIAN-PACKAGE: imports MODULE, else installs it with pip (plain, else with
# --break-system-packages for an externally managed Python), else with apt
python_module() {
  if ! python3 -c "import $1" >/dev/null 2>&1; then
    echo "ensure-deps: installing $2" >&2
    python3 -m pip install --quiet "$2" 2>/dev/null \
      || python3 -m pip install --quiet --break-system-packages "$2" 2>/dev/null \
      || apt_install "$3"
  fi
}
if ! { command -v pkg-config >/dev/null 2>&1 && pkg-config --exists hdf5; }; then
  echo "ensure-deps: installing libhdf5-dev pkg-config" >&2
  apt_install libhdf5-dev pkg-config
fi
if [ "${1:-}" = "--with-h5py" ]; then
  if ! command -v python3 >/dev/null 2>&1; then
    echo "ensure-deps: installing python3" >&2
    apt_install python3 python3-pip
  fi
  python_module h5py h5py python3-h5py
fi
if [ "${1:-}" = "--with-browser" ] || [ "${2:-}" = "--with-browser" ]; then
  if ! command -v chromium-headless-shell >/dev/null 2>&1 || ! command -v pdftoppm >/dev/null 2>&1; then
    echo "ensure-deps: installing chromium-headless-shell poppler-utils" >&2
    apt_install chromium-headless-shell poppler-utils
  fi
  if ! command -v python3 >/dev/null 2>&1; then
    echo "ensure-deps: installing python3" >&2
    apt_install python3 python3-pip
  fi
  python_module html5lib html5lib python3-html5lib
fi
