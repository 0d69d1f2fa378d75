# Helpers for the sweep tests (sourced): failing with a message, and a CSV without its timing columns.
fail() {
  echo "FAIL: $*" >&2
  exit 1
}

# non_timing CSV: the table without the columns that are timings or follow from them (a header ending in
# _ms, "seconds", and "pareto", which is decided by cost). Cells are split at commas outside double quotes
# (RFC 4180, as CsvTable writes them) and kept as written; the process id in the stress suite's temporary
# folder is blanked.
non_timing() {
  awk 'function split_csv(line, cells,    n, i, c, quoted, cell) {
         n = 0; cell = ""; quoted = 0
         for (i = 1; i <= length(line); ++i) {
           c = substr(line, i, 1)
           if (c == "\"") quoted = !quoted
           if (c == "," && !quoted) { cells[++n] = cell; cell = "" } else cell = cell c
         }
         cells[++n] = cell
         return n
       }
       { n = split_csv($0, cells); out = ""
         for (i = 1; i <= n; ++i) {
           if (NR == 1) drop[i] = (cells[i] ~ /_ms$/ || cells[i] == "seconds" || cells[i] == "pareto")
           if (!drop[i]) out = out (out == "" ? "" : ",") cells[i]
         }
         print out }' "$1" |
    sed -E 's/deform_stress_[0-9]+/deform_stress_<pid>/g'  # the stress meshes' folder is named by process
}

# same_measures A B: the two CSVs agree in every non-timing column, and have rows.
same_measures() {
  [[ -s "$1" && -s "$2" ]] || fail "missing table: $1 or $2"
  diff <(non_timing "$1") <(non_timing "$2") > /dev/null || {
    diff <(non_timing "$1") <(non_timing "$2") | head -10 >&2
    fail "$1 and $2 differ outside the timing columns"
  }
  [[ $(wc -l < "$1") -gt 1 ]] || fail "$1 has no rows"
}
