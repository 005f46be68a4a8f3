#!/usr/bin/env bash
# Every repository path named in the docs and in comments exists (CTest: Docs.EveryNamedPathExists).
#
# Usage: scripts/check-doc-paths.sh [REPO_ROOT]   (default: the folder above this script)
# Exit status 0 when every named path exists; 1, listing each missing one as FILE:LINE: PATH.
# Bash, grep, sed, find and coreutils only: it runs on a bare Debian 12.
#
# What is scanned:
#   - README.md and docs/*.md, every line (code blocks too);
#   - the comments of src/, include/, apps/, tests/, bench/, fuzz/ (C++ and CUDA: the text after
#     the first // or /* on a line), of scripts/*.sh, bench/*.sh, .ci/run, the cmake folder where
#     there is one and every CMakeLists.txt (the text after a # at the start of a line or after a
#     blank).
#
# What is a path, and how it is checked:
#   1. A token that starts with a top-level folder of the repository (apps, bench, cmake, docs,
#      fuzz, include, scenes, scripts, src, tests, .ci, then a /), or with ./ before one: it must
#      exist (file or folder) from the repository root.
#   2. A token with a / that names a source or document (.cpp .hpp .h .cc .cu .cuh .md .sh .cmake
#      .py) but starts elsewhere (src/'s `report/pictures.hpp`, `dentsph/limits.hpp`, a relative
#      `../docs/model.md`): it must exist from the file's own folder or its parent, the
#      repository root, src/, include/, include/dentsph/, apps/ or tests/.
#   3. A bare file name with one of those extensions (`model.md`, `cpu_stepper.cpp`): a file of
#      that name, in that case, must exist somewhere in the repository (outside build/, out/,
#      Testing/). `camera.hpp/.cpp` names both files.
#   4. In Markdown, a link's target `[text](target)` (not a URL, not an #anchor alone): its file
#      part must exist from the document's folder.
#   The #anchor after a path is not checked here.
#
# What is not a repository path (skipped):
#   - URLs (a token with ://, or www.), absolute paths (/tmp, /usr/...), home paths (~/...),
#     paths above the repository (../shared/...: the project's test data sits beside it);
#   - what a run or a build writes: tokens that start with build/, out/, Testing/, or name a
#     file under one of them;
#   - placeholders: a token with * < > { } $ @ or ..., or one of whose folders is written in
#     capitals (DIR/report.html, OUT/recording, BUILD/...);
#   - files a run writes (.json .csv .html .png .svg .txt .stl .ply .obj .vtu .pvd ...) named
#     bare or under a folder that is not the repository's: they are checked only under rule 1;
#   - the names and prefixes listed in scripts/doc-paths-allow.txt (one a line, # comments; a
#     line ending in / allows every path under it; a line may use shell wildcards).

set -u
root=${1:-$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)}
cd "$root" || { echo "check-doc-paths: cannot enter $root" >&2; exit 2; }

allow_file=scripts/doc-paths-allow.txt
allow=()
if [[ -f $allow_file ]]; then
  while IFS= read -r line || [[ -n $line ]]; do
    line=${line%%#*}
    line=${line%"${line##*[![:space:]]}"}
    line=${line#"${line%%[![:space:]]*}"}
    [[ -n $line ]] && allow+=("$line")
  done <"$allow_file"
fi

top_level='apps|bench|cmake|docs|fuzz|include|scenes|scripts|src|tests|\.ci'
src_ext='cpp|hpp|h|cc|cu|cuh|md|sh|cmake|py'

# Every file's name in the repository (rule 3).
declare -A names=()
while IFS= read -r f; do
  names[${f##*/}]=1
done < <(find . \( -path ./build -o -path ./out -o -path ./Testing -o -path ./.git \) -prune -o -type f -print)

missing=0
declare -A reported=()
report() {  # FILE LINE PATH (once each)
  local key="$1:$2: $3"
  [[ -n ${reported[$key]+x} ]] && return
  reported[$key]=1
  echo "$key"
  missing=$((missing + 1))
}

allowed() {  # PATH
  local p=$1 a
  for a in "${allow[@]+"${allow[@]}"}"; do
    if [[ $a == */ ]]; then
      [[ $p == "$a"* ]] && return 0
    else
      # shellcheck disable=SC2053
      [[ $p == $a ]] && return 0
    fi
  done
  return 1
}

placeholder() {  # PATH: a folder or name in capitals, or a wildcard
  local p=$1 part
  case $p in *'*'* | *'<'* | *'>'* | *'{'* | *'}'* | *'$'* | *'@'* | *'...'*) return 0 ;; esac
  local IFS=/
  for part in $p; do
    [[ $part =~ ^[A-Z][A-Z0-9_]*$ ]] && return 0
  done
  return 1
}

check_token() {  # FILE LINE TOKEN
  local file=$1 line=$2 t=$3 dir base
  # Trim what surrounds a path in prose: an include's < >, a sentence's full stop.
  t=${t#<}
  while [[ $t == *. || $t == *'>' ]]; do t=${t%?}; done
  [[ -z $t ]] && return
  case $t in
    *://* | www.* | /* | '~'* | ../../* ) return ;;
  esac
  placeholder "$t" && return
  allowed "$t" && return
  local p=${t#./}
  case $p in
    build/* | out/* | Testing/* | build | out) return ;;
  esac
  dir=${file%/*}
  [[ $dir == "$file" ]] && dir=.
  if [[ $p =~ ^([^/]+)\.(hpp|h)/\.(cpp|cu)$ ]]; then  # camera.hpp/.cpp: both files
    local stem=${BASH_REMATCH[1]} header=${BASH_REMATCH[2]} source=${BASH_REMATCH[3]}
    check_token "$file" "$line" "$stem.$header"
    check_token "$file" "$line" "$stem.$source"
    return
  fi
  if [[ $p =~ ^($top_level)/ ]]; then
    [[ -e $p ]] || report "$file" "$line" "$t"
    return
  fi
  if [[ $p == */* ]]; then
    [[ $p =~ \.($src_ext)$ ]] || return
    [[ $p == ../* && $dir == . ]] && return  # above the repository
    for base in "$dir" "${dir%/*}" . src include include/dentsph apps tests; do
      [[ -e $base/$p ]] && return
    done
    report "$file" "$line" "$t"
    return
  fi
  [[ $p =~ ^[A-Za-z0-9_][A-Za-z0-9_.+-]*\.($src_ext)$ ]] || return
  [[ -n ${names[$p]+x} ]] || report "$file" "$line" "$t"
}

token_re='[A-Za-z0-9_./~*{}$<>@+-]+'

scan() {  # FILE TEXT_FILE: TEXT_FILE holds FILE's lines, what is not to be scanned blanked out
  local file=$1 entry n tok
  while IFS= read -r entry; do
    n=${entry%%:*}
    tok=${entry#*:}
    check_token "$file" "$n" "$tok"
  done < <(grep -noE "$token_re" "$2" | grep -E '^[0-9]+:.*(/|\.[A-Za-z]+$)')
}

markdown_links() {  # FILE: rule 4
  local file=$1 dir n target entry
  dir=${file%/*}
  [[ $dir == "$file" ]] && dir=.
  while IFS= read -r entry; do
    n=${entry%%:*}
    target=${entry#*:}
    target=${target#](}
    target=${target%)}
    target=${target%% *}
    target=${target%%#*}
    case $target in '' | *://* | mailto:*) continue ;; esac
    [[ -e $dir/$target ]] || report "$file" "$n" "$target"
  done < <(grep -noE '\]\([^)[:space:]]+( "[^"]*")?\)' "$file")
}

text=$(mktemp)
trap 'rm -f "$text"' EXIT

for f in README.md docs/*.md; do
  [[ -f $f ]] || continue
  scan "$f" "$f"
  markdown_links "$f"
done

# C++ and CUDA: keep the text after the first // or /* of a line, blank the rest (lines stay put).
while IFS= read -r f; do
  sed -E 's#^([^/]|/[^/*])*(//|/\*)##; t; s/.*//' "$f" >"$text"
  scan "$f" "$text"
done < <(find src include apps tests bench fuzz -type f \( -name '*.cpp' -o -name '*.hpp' -o -name '*.h' \
           -o -name '*.cc' -o -name '*.cu' -o -name '*.cuh' -o -name '*.in' \) 2>/dev/null | sort)

# Shell and CMake: the text after a # at the start of a line or after a blank.
while IFS= read -r f; do
  f=${f#./}
  sed -E 's/^(([^#]*[[:space:]])?)#//; t; s/.*//' "$f" >"$text"
  scan "$f" "$text"
done < <({ find scripts bench -maxdepth 1 -type f -name '*.sh'
           find . \( -path ./build -o -path ./out -o -path ./Testing -o -path ./.git \) -prune -o -name CMakeLists.txt -print
           [[ -d cmake ]] && find cmake -type f
           [[ -f .ci/run ]] && echo .ci/run; } 2>/dev/null | sort)

if ((missing > 0)); then
  echo "check-doc-paths: $missing named path(s) do not exist (rules: the header of scripts/check-doc-paths.sh;" \
    "allowed names: $allow_file)" >&2
  exit 1
fi
echo "check-doc-paths: every named path exists"
