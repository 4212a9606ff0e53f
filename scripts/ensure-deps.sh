#!/usr/bin/env bash
# Installs the system packages the build needs when they are missing.
# GMP's build (pulled in by rug for the `mpfr` feature) needs GNU m4; Debian's
# own GMP is too old for rug's `use-system-libs`, so GMP and MPFR are built
# from source by gmp-mpfr-sys and cached in the user cache directory.
set -euo pipefail
missing=()
command -v m4 >/dev/null 2>&1 || missing+=(m4)
command -v make >/dev/null 2>&1 || missing+=(make)
command -v cc >/dev/null 2>&1 || missing+=(gcc)
if [ "${#missing[@]}" -eq 0 ]; then exit 0; fi
echo "ensure-deps: installing ${missing[*]}" >&2
SUDO=""
if [ "$(id -u)" -ne 0 ]; then SUDO="sudo"; fi
if command -v apt-get >/dev/null 2>&1; then
  $SUDO apt-get update -qq
  DEBIAN_FRONTEND=noninteractive $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
elif command -v dnf >/dev/null 2>&1; then
  $SUDO dnf install -y "${missing[@]}"
elif command -v brew >/dev/null 2>&1; then
  brew install "${missing[@]}"
else
  echo "ensure-deps: please install: ${missing[*]}" >&2
  exit 1
fi
