#!/usr/bin/env bash
# Headers for building against Debian's LAMMPS that liblammps-dev leaves out
# (fmt/, neigh_request.h, exceptions.h, command.h, lammpsplugin.h, ...), from
# the Debian source package of exactly the installed version. apt runs with a
# private sources list and state under $2, so the system's apt set-up is not
# touched.
#   usage: fetch_lammps_headers.sh DEST_DIR WORK_DIR
set -euo pipefail
dest=$(realpath -m "$1")
work=$(realpath -m "$2")
version=$(dpkg-query -W -f='${source:Version}' liblammps-dev)
mkdir -p "$work/lists/partial" "$work/cache/archives/partial" "$dest"
cat > "$work/sources.list" <<LIST
deb-src [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian bookworm main
LIST
apt_opts=(-o "Dir::Etc::SourceList=$work/sources.list" -o Dir::Etc::SourceParts=/dev/null
          -o "Dir::State::Lists=$work/lists" -o "Dir::Cache=$work/cache"
          -o APT::Sandbox::User=root -qq)
apt-get "${apt_opts[@]}" update
(cd "$work" && apt-get "${apt_opts[@]}" source --download-only "lammps=$version")
tar -xJf "$work"/lammps_*.orig.tar.xz -C "$dest" --strip-components=2 --wildcards '*/src/*.h' '*/src/fmt/*'
rm -rf "$work"
echo "LAMMPS $version headers in $dest"
