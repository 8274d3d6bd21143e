# The spinning book: w's components, and K and |H| relative to their start, from the book program's results.
#   gnuplot -p handouts/plots/book.gp                         a window (after build/bin/book --spin ... here)
#   gnuplot -e "out='book.png'" handouts/plots/book.gp        a PNG instead
#   gnuplot -e "results='other.txt'" handouts/plots/book.gp   another results file
if (!exists("results")) results = "BookSpinResults-min.txt"
if (exists("out")) { set terminal pngcairo size 900,700; set output out }
if (!exists("out") && GPVAL_TERM eq "unknown") {
  print "This gnuplot has no window (gnuplot-nox): add -e \"out='plot.png'\" for a PNG, or use the lab program's --plot."
  exit status 1
}

stats results using 9 every ::1::1 nooutput name "K"   # the first row after the header: K(0)
stats results using 8 every ::1::1 nooutput name "H"   # and |H|(0)
set key autotitle columnhead
set grid
set multiplot layout 2,1 title "The spinning book"
set ylabel "angular velocity in the book's axes (rad/s)"
plot results using 1:2 with lines linewidth 2 title "wx", '' using 1:3 with lines linewidth 2 title "wy", \
     '' using 1:4 with lines linewidth 2 title "wz"
set xlabel "time t (s)"
set ylabel "relative change"
set format y "%.1e"
plot results using 1:($9 / K_min - 1) with lines title "K / K(0) - 1", \
     '' using 1:($8 / H_min - 1) with lines title "|H| / |H|(0) - 1"
unset multiplot
