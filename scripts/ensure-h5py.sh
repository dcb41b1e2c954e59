#!/bin/sh
# Makes sure python3 can `import h5py` (needed by tests/store.rs, which checks the HDF5 run-file layout
# with h5py). Installs it with pip if missing; falls back to the Debian package if pip is unavailable.
set -e
if python3 -c 'import h5py' >/dev/null 2>&1; then
    exit 0
fi
if python3 -m pip --version >/dev/null 2>&1; then
    echo "ensure-h5py: installing h5py with pip" >&2
    python3 -m pip install --quiet h5py || python3 -m pip install --quiet --user h5py || \
        python3 -m pip install --quiet --break-system-packages h5py
elif command -v apt-get >/dev/null 2>&1; then
    echo "ensure-h5py: pip unavailable, installing python3-h5py with apt-get" >&2
    apt-get install -y python3-h5py
else
    echo "ensure-h5py: neither pip nor apt-get is available; install h5py for python3 by hand" >&2
    exit 1
fi
python3 -c 'import h5py' || { echo "ensure-h5py: h5py still cannot be imported" >&2; exit 1; }
