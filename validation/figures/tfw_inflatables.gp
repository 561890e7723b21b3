set terminal pngcairo size 1000,420
set output 'validation/results/../figures/tfw_inflatables.png'
set xlabel 'angle about the vertical axis [deg]'
set ylabel 'wrinkle displacement off the base [mm]'
set title 'TFW inflatables, cut f = 0.25 above the seam'
set xrange [-180:180]
set xtics 45
set key outside right top
plot 'validation/results/tfw_inflatables_rings.dat' u 1:2 w l t 'torus (outer)', '' u 1:3 w l t 'Mylar balloon', '' u 1:4 w l t 'teabag'
