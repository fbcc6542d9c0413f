# Samples a history.csv column at fixed times by linear interpolation between steps (the step
# times of a run need not fall on the sampling grid: Δt is cut and regrown).
# Usage: awk -F, -v column=4 -v every=0.05 -v name=ux -f scripts/sample_history.awk history.csv
NR == 1 { print "time," name; next }
{
  t = $1 + 0; v = $column + 0
  if (NR == 2) { next_t = 0 }
  while (next_t <= t + 1e-12) {
    if (NR == 2 || t == pt) value = v
    else value = pv + (v - pv) * (next_t - pt) / (t - pt)
    printf "%.2f,%.9g\n", next_t, value
    k++; next_t = k * every
  }
  pt = t; pv = v
}
