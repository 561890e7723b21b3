set terminal pngcairo size 1000,420
set output 'validation/results/../figures/tfw_sphere_drape.png'
set xlabel 'angle on the rest circle [deg]'
set ylabel 'wrinkle displacement off the base [mm]'
set title 'TFW sphere drape, 1681-vertex base'
set xrange [0:360]
set xtics 45
set key outside right top
plot 'validation/results/tfw_sphere_drape_ring.dat' u 1:2 w l t 'r = 0.30 m', '' u 1:3 w l t 'r = 0.35 m', '' u 1:4 w l t 'r = 0.40 m'
