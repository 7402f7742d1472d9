#!/bin/sh
# The C++ sources follow the repository's .clang-format (Debian 12's clang-format 14): exits non-zero and names each
# place that `make format` would change. The check checks itself first: a well-formatted probe must pass and the same
# probe mis-indented must fail, so a missing style file or a clang-format that accepts anything is caught.
set -eu
root=${1:-.}
cd "$root"
style="--style=file:$(pwd)/.clang-format"
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
printf 'int f(int a) {\n    if (a) return 1;\n    return 2;\n}\n' > "$dir/good.cpp"
printf 'int f(int a) {\n  if (a) return 1;\n  return 2;\n}\n' > "$dir/bad.cpp"
if ! clang-format "$style" --dry-run -Werror "$dir/good.cpp"; then
    echo "check_format: a well-formatted probe was rejected" >&2; exit 1
fi
if clang-format "$style" --dry-run -Werror "$dir/bad.cpp" 2>/dev/null; then
    echo "check_format: a mis-indented probe was accepted: the check cannot fail" >&2; exit 1
fi
files=$(find native tests bench -name '*.cpp' -o -name '*.h' | sort)
clang-format "$style" --dry-run -Werror $files
echo "check_format: $(echo "$files" | wc -l) files follow .clang-format"
