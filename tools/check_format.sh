#!/usr/bin/env bash
# Fails when a tracked C++/CUDA file differs from what clang-format (the repository's .clang-format) makes
# of it, naming the files. Exit 77 (a skip for ctest) where clang-format or git is missing.
set -euo pipefail
cd "$(dirname "$0")/.."
command -v clang-format >/dev/null && command -v git >/dev/null && git rev-parse --git-dir >/dev/null 2>&1 ||
  { echo "check_format: clang-format or a git checkout missing: skipped"; exit 77; }
bad=()
while IFS= read -r f; do
  clang-format --dry-run --Werror "$f" >/dev/null 2>&1 || bad+=("$f")
done < <(git ls-files '*.cpp' '*.hpp' '*.cu' '*.cuh')
if ((${#bad[@]})); then
  echo "check_format: not clang-format clean (run clang-format -i on them): ${bad[*]}"
  exit 1
fi
echo "check_format: all tracked C++/CUDA files are clang-format clean"
