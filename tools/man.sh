#!/bin/sh
# man.sh BIN: the manual page archquake(1), in roff on stdout, written from
# BIN's own --help texts: the main job's (with the list of commands; its
# Environment and Files become ENVIRONMENT and FILES), each listed
# command's, and `BIN help arch-file` (the arch file's sections and keys,
# printed from the table its parser reads) as ARCH FILE.  `make` writes it
# to build/archquake.1, so the page and the program cannot drift apart.
set -eu
bin=$1
case $bin in */*) ;; *) bin=./$bin ;; esac
tmp=$(mktemp -d)
trap 'rm -rf "$tmp"' EXIT

# Plain text as roff: backslashes and minus signs escaped, a leading . or '
# (a roff control line) protected with \&.
roff() {
  sed -e 's/\\/\\e/g' -e 's/-/\\-/g' -e "s/^\\([.']\\)/\\\\\\&\\1/"
}
# A help text as a no-fill block.
block() {
  printf '.nf\n'
  roff < "$1"
  printf '.fi\n'
}

"$bin" --help > "$tmp/all"
"$bin" help arch-file > "$tmp/arch"
version=$("$bin" --version)
# the main --help up to its Environment, which has a section of its own, as
# has Files
awk '/^Environment:$/ { s = 1 } !s' "$tmp/all" > "$tmp/main"
awk '/^Files:$/ { s = 0 } s; /^Environment:$/ { s = 1 }' "$tmp/all" > "$tmp/env"
awk 's; /^Files:$/ { s = 1 }' "$tmp/all" > "$tmp/files"
for f in env files arch; do
  [ -s "$tmp/$f" ] || { echo "man.sh: $bin gives no $f text" >&2; exit 1; }
done
commands=$(awk '/^Commands/ { c = 1 } c && $1 == "archquake" && $2 ~ /^[a-z]/ { print $2 }' "$tmp/main")
[ -n "$commands" ] || { echo "man.sh: $bin --help lists no commands" >&2; exit 1; }
for c in $commands; do
  "$bin" "$c" --help > "$tmp/cmd-$c"
done

printf '.TH ARCHQUAKE 1 "" "%s" "User Commands"\n' "$version"
printf '.nh\n'
printf '.SH NAME\n'
printf 'archquake \\- screen masonry arches against earthquake records (work-path method)\n'
printf '.SH SYNOPSIS\n.nf\n'
for f in "$tmp/main" $(for c in $commands; do printf '%s ' "$tmp/cmd-$c"; done); do
  grep '^usage: ' "$f" | sed 's/^usage: //' | roff
done
printf '.fi\n'
printf '.SH DESCRIPTION\n'
printf 'The text below is \\fBarchquake \\-\\-help\\fR; each command'"'"'s follows under\n'
printf '.BR COMMANDS ,\n'
printf 'as \\fBarchquake\\fR \\fICOMMAND\\fR \\fB\\-\\-help\\fR prints it.\n.PP\n'
block "$tmp/main"
printf '.SH COMMANDS\n'
for c in $commands; do
  printf '.SS %s\n' "$c"
  block "$tmp/cmd-$c"
done
printf '.SH "ARCH FILE"\n'
printf 'As \\fBarchquake help arch\\-file\\fR prints it.\n.PP\n'
block "$tmp/arch"
printf '.SH ENVIRONMENT\n'
block "$tmp/env"
printf '.SH FILES\n'
block "$tmp/files"
printf '.SH "SEE ALSO"\n'
printf '.BR h5dump (1),\n.BR mpirun (1);\n'
printf 'README.md and docs/*.md (the method, every format, the arch file, the\n'
printf 'results file'"'"'s layout), installed in share/doc/archquake beside share/man.\n'
