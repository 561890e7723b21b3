set terminal pngcairo size 1000,420
set output 'validation/results/../figures/tfw_twisted_cylinder.png'
set xlabel 'angle [deg]'
set ylabel 'radial wrinkle displacement [mm]'
set title 'TFW twisted cylinder, z = 2.5 m, 1341-vertex base'
set xrange [-180:180]
set xtics 45
plot 'validation/results/tfw_twisted_cylinder_ring.dat' w l notitle
