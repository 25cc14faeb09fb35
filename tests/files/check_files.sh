#!/usr/bin/env bash
# Runs statmc on every file of a corpus and classifies each run: ok (exit 0 and a readable
# output), error (exit 1 and a "statmc: error:" line naming the file), crash (a signal, a
# sanitizer report, or any other exit), hang (over LIMIT seconds) or noise (library text on
# stderr), and silent (exit 0 with an unreadable output or other pixels). Usage:
#   check_files.sh STATMC DIR            DIR/manifest.txt says what each file must end in
#   check_files.sh STATMC FILE...        ok or error is accepted of every file
# With OIIOTOOL=/path/to/oiiotool, oiiotool runs the same files (FILE -o OUT) for the table
# in docs/reliability.md. LIMIT (default 10) is the seconds one run may take.
set -uo pipefail
statmc=$1
shift
limit=${LIMIT:-10}
work=$(mktemp -d "${TMPDIR:-/tmp}/statmc-files.XXXXXX")
trap 'rm -rf "$work"' EXIT

declare -A expected
files=()
if [[ $# -eq 1 && -f "$1/manifest.txt" ]]; then
    while read -r file copy denoise info reference; do
        files+=("$1/$file")
        [[ $reference == - ]] || expected["$1/$file reference"]="$1/$reference"
        expected["$1/$file copy"]=$copy
        expected["$1/$file denoise"]=$denoise
        expected["$1/$file info"]=$info
    done <"$1/manifest.txt"
else
    files=("$@")
fi
[[ ${#files[@]} -gt 0 ]] || { echo "check_files.sh: no files given" >&2; exit 2; }

# classify RUN FILE OUTPUT CMD...: prints the outcome of one run; its stderr stays in
# $work/RUN.err. A successful copy of a file with a reference must have its pixels.
classify() {
    local run=$1 file=$2 output=$3
    shift 3
    local reference=${expected["$file reference"]:-}
    rm -f "$output"
    local err="$work/$run.err"
    local start=$SECONDS
    timeout -s KILL "$limit" "$@" >/dev/null 2>"$err" </dev/null
    local rc=$?
    # Killed at the limit is a hang; killed sooner (the OOM killer) is a crash.
    if [[ $rc -eq 137 ]]; then
        if (( SECONDS - start >= limit )); then echo hang; else echo crash; fi
        return
    fi
    if grep -qE "Sanitizer|runtime error:|terminate called|Assertion .* failed" "$err"; then
        echo crash; return
    fi
    if [[ $rc -eq 0 ]]; then
        if [[ -n "$output" ]] &&
            ! timeout -s KILL "$limit" "$statmc" "$output" --echo "" >/dev/null 2>&1; then
            echo "silent"; return  # exit 0 with no readable output
        fi
        if [[ $run == copy && -n $reference ]] &&
            ! timeout -s KILL "$limit" "$statmc" "$output" "$reference" --diff >/dev/null 2>&1; then
            echo "silent"; return  # exit 0 with other pixels
        fi
        if grep -qvE "^(statmc|--[a-z-]+): (warning|note): " "$err" && [[ -s "$err" ]]; then
            echo noise; return
        fi
        echo ok; return
    fi
    if [[ $rc -eq 1 ]]; then
        # Exactly the error line(s), each naming the file; nothing from the libraries.
        if grep -qvE "^(statmc: error|(statmc|--[a-z-]+): (warning|note)): " "$err" ||
            ! grep -qF "$file" "$err"; then
            echo noise; return
        fi
        echo error; return
    fi
    echo crash
}

# outcome_matches WANT GOT
outcome_matches() {
    [[ $1 == "$2" || ( $1 == either && ( $2 == ok || $2 == error ) ) ]]
}

failures=0
declare -A tally
printf '%-40s %-8s %-8s %-8s%s\n' file copy denoise info "${OIIOTOOL:+ oiiotool}"
for file in "${files[@]}"; do
    copy=$(classify copy "$file" "$work/copy.exr" "$statmc" "$file" -o "$work/copy.exr")
    denoise=$(classify denoise "$file" "$work/denoised.exr" "$statmc" "$file" --denoise -o "$work/denoised.exr")
    info=$(classify info "$file" "" "$statmc" --info -v "$file")
    line=$(printf '%-40s %-8s %-8s %-8s' "$(basename "$file")" "$copy" "$denoise" "$info")
    if [[ -n ${OIIOTOOL:-} ]]; then
        rm -f "$work/o.exr"
        timeout -s KILL "$limit" "$OIIOTOOL" "$file" -o "$work/o.exr" >/dev/null 2>&1 </dev/null
        rc=$?
        theirs=$([[ $rc -eq 137 ]] && echo hang || { [[ $rc -gt 128 ]] && echo crash || echo "exit$rc"; })
        line+=" $theirs"
        tally["oiiotool $theirs"]=$(( ${tally["oiiotool $theirs"]:-0} + 1 ))
    fi
    bad=""
    for run in copy denoise info; do
        got=${!run}
        tally["statmc $got"]=$(( ${tally["statmc $got"]:-0} + 1 ))
        want=${expected["$file $run"]:-either}
        if ! outcome_matches "$want" "$got"; then
            bad+=" $run: wanted $want, got $got;"
        fi
    done
    echo "$line${bad:+   <-- FAIL$bad}"
    [[ -z $bad ]] || head -q -n 3 "$work"/*.err | sed "s/^/    /"
    [[ -z $bad ]] || failures=$((failures + 1))
done
echo "== runs:" $(for k in "${!tally[@]}"; do echo "$k=${tally[$k]};"; done | sort)
echo "== ${#files[@]} files, $failures with an unexpected outcome"
[[ $failures -eq 0 ]]
