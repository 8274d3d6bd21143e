# Projectile motion: the simulated path y(x) against the exact parabola, from the projectile program's results.
#   gnuplot -p handouts/plots/projectile.gp                          a window (after build/bin/projectile here)
#   gnuplot -e "out='projectile.png'" handouts/plots/projectile.gp   a PNG instead
# The parabola drawn is the lab's: 44.7 m/s at 35 degrees, g = 9.8 m/s^2.
if (!exists("results")) results = "ProjectileMotionResults.txt"
if (exists("out")) { set terminal pngcairo size 900,500; set output out }
if (!exists("out") && GPVAL_TERM eq "unknown") {
  print "This gnuplot has no window (gnuplot-nox): add -e \"out='plot.png'\" for a PNG, or use the lab program's --plot."
  exit status 1
}

v0 = 44.7; theta = 35 * pi / 180; g = 9.8
parabola(x) = tan(theta) * x - g * x**2 / (2 * (v0 * cos(theta))**2)

set key autotitle columnhead
set grid
set title "A baseball at 44.7 m/s and 35 degrees"
set xlabel "range x (m)"
set ylabel "height y (m)"
set xrange [0:195]
set yrange [0:*]
plot results using 2:3 every 20 with points pointtype 7 pointsize 0.8 title "Simbody (every 20th sample)", \
     parabola(x) with lines linewidth 2 title "exact: tan(35) x - 4.9 x^2 / (44.7 cos(35))^2"
