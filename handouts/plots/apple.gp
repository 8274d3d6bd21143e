# Newton's apple: the simulated fall against the exact one, from the apple program's results file.
#   gnuplot -p handouts/plots/apple.gp                          a window (after build/bin/apple in this folder)
#   gnuplot -e "out='apple.png'" handouts/plots/apple.gp        a PNG instead
#   gnuplot -e "results='other.txt'" handouts/plots/apple.gp    another results file
if (!exists("results")) results = "NewtonsAppleResults.txt"
if (exists("out")) { set terminal pngcairo size 900,700; set output out }
if (!exists("out") && GPVAL_TERM eq "unknown") {
  print "This gnuplot has no window (gnuplot-nox): add -e \"out='plot.png'\" for a PNG, or use the lab program's --plot."
  exit status 1
}

set key autotitle columnhead
set grid
set multiplot layout 2,1 title "Newton's apple: dropped from rest at 10 m"
set ylabel "height y (m)"
plot results using 1:2 every 20 with points pointtype 7 pointsize 0.8 title "Simbody (every 20th sample)", \
     10 - 4.9 * x**2 with lines linewidth 2 title "exact: 10 - 4.9 t^2"
set xlabel "time t (s)"
set ylabel "velocity y' (m/s)"
plot results using 1:3 every 20 with points pointtype 7 pointsize 0.8 title "Simbody (every 20th sample)", \
     -9.8 * x with lines linewidth 2 title "exact: -9.8 t"
unset multiplot
