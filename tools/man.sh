#!/bin/sh
# man.sh BIN: the manual page archquake(1), in roff on stdout, written from
# BIN's own --help texts: the main job's (with the list of commands) and
# each listed command's.  `make` writes it to build/archquake.1, so the page
# and --help cannot drift apart.
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

"$bin" --help > "$tmp/main"
version=$("$bin" --version)
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
printf '.SH SEE ALSO\n'
printf 'README.md and docs/*.md, installed in share/doc/archquake beside share/man.\n'
