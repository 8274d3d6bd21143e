# The baby boot: the rod's swing qA and the plate's turn qB, and the energy, from the babyboot program's results.
#   gnuplot -p handouts/plots/babyboot.gp                          a window (after build/bin/babyboot here)
#   gnuplot -e "out='babyboot.png'" handouts/plots/babyboot.gp     a PNG instead
#   gnuplot -e "results='other.txt'" handouts/plots/babyboot.gp    another results file
if (!exists("results")) results = "babybootResults.txt"
if (exists("out")) { set terminal pngcairo size 900,700; set output out }
if (!exists("out") && GPVAL_TERM eq "unknown") {
  print "This gnuplot has no window (gnuplot-nox): add -e \"out='plot.png'\" for a PNG, or use the lab program's --plot."
  exit status 1
}

set key autotitle columnhead
set grid
set multiplot layout 2,1 title "The swinging baby boot"
set ylabel "angle (deg)"
plot results using 1:2 with lines linewidth 2 title "qA, the rod's swing", \
     '' using 1:3 with lines linewidth 2 title "qB, the plate's turn about the rod"
set xlabel "time t (s)"
set ylabel "energy (J)"
set format y "%.1e"
plot results using 1:6 with lines title "kinetic + potential energy (0 at the start)"
unset multiplot
