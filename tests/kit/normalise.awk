# tests/kit/normalise.awk: each line with its runs of blanks made one space and its ends trimmed;
# a unified diff's marker column ("+", "-" or " ") is trimmed too, so a patch's lines are the lines
# it quotes.  With -v where=1 each line is printed as FILE:LINE:TEXT (FILE without a leading ./).
{
    gsub(/[ \t\r]+/, " "); sub(/^[-+ ] ?/, ""); sub(/^ /, ""); sub(/ $/, "")
    if (where) { f = FILENAME; sub(/^\.\//, "", f); print f ":" FNR ":" $0 } else print
}
