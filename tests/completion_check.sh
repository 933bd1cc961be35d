#!/bin/bash
# The bash completion of casteljau (app/casteljau.bash-completion) against the built tool:
# command names at the first word, each command's options after a dash.
# usage: completion_check.sh COMPLETION_FILE CASTELJAU_EXE
set -u
source "$1"
exe=$2
fail=0
complete_words() { # words... -> COMPREPLY for the last one
    COMP_WORDS=("$exe" "$@")
    COMP_CWORD=$#
    COMPREPLY=()
    _casteljau
    echo "${COMPREPLY[*]}"
}
expect() { # description, got, want
    if [[ $2 == "$3" ]]; then echo "ok: $1 -> '$2'"; else echo "FAILED: $1 -> '$2', want '$3'"; fail=1; fi
}
expect "casteljau ren" "$(complete_words ren)" "render"
expect "casteljau t" "$(complete_words t)" "tessellate trace"
expect "casteljau render --sp" "$(complete_words render --sp)" "--spp"
expect "casteljau trace --ind" "$(complete_words trace --ind)" "--indirect"
expect "casteljau animate --checkpoint-e" "$(complete_words animate --checkpoint-e)" "--checkpoint-every"
expect "casteljau eval --qu" "$(complete_words eval --qu)" "--quiet"
n=$(complete_words "" | wc -w)
if [[ $n -ge 11 ]]; then echo "ok: $n command names and --help, --version at the first word"; else echo "FAILED: only $n words at the first word"; fail=1; fi
exit $fail
