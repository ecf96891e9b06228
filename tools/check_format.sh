#!/usr/bin/env bash
# Checks that every C++ file under src/ and tests/ is formatted by the checked-in .clang-format (Google style,
# 120 columns). Exits 1 and lists the files that differ; `bash tools/check_format.sh --fix` reformats them.
# CI runs it (.ci/run) before the tests. Installs clang-format (Debian package clang-format) when missing, as root.
#   bash tools/check_format.sh [--fix]
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

if ! command -v clang-format >/dev/null 2>&1; then
  [ "$(id -u)" -eq 0 ] || { echo "tools/check_format.sh: ERROR: clang-format is missing: apt-get install -y clang-format" >&2; exit 1; }
  echo "tools/check_format.sh: installing the Debian package clang-format"
  export DEBIAN_FRONTEND=noninteractive
  apt-get install -y --no-install-recommends clang-format >/dev/null 2>&1 ||
    { apt-get update >/dev/null && apt-get install -y --no-install-recommends clang-format; }
fi

mapfile -t files < <(git ls-files 'src/*.cpp' 'src/*.hpp' 'tests/*.cpp' 'tests/*.hpp')
if [ "${1:-}" = "--fix" ]; then
  clang-format -i "${files[@]}"
  echo "tools/check_format.sh: formatted ${#files[@]} files"
  exit 0
fi
bad=()
for f in "${files[@]}"; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done
if ((${#bad[@]} > 0)); then
  echo "tools/check_format.sh: ERROR: ${#bad[@]} of ${#files[@]} files differ from .clang-format ($(clang-format --version)):" >&2
  printf '  %s\n' "${bad[@]}" >&2
  echo "tools/check_format.sh: run 'bash tools/check_format.sh --fix' and commit the result" >&2
  exit 1
fi
echo "tools/check_format.sh: all ${#files[@]} C++ files match .clang-format"
