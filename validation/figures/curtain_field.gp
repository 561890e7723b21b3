set terminal pngcairo size 700,700
set output 'validation/results/../figures/curtain_field.png'
set view map
set size ratio -1
set xlabel 'x [mm]'
set ylabel 'depth [mm]'
set yrange [80:0]
set cblabel 'z [mm]'
set palette defined (-1 'blue', 0 'white', 1 'red')
set title 'out-of-plane z, B = 2e-06 N m'
splot 'validation/results/curtain_field.dat' u 2:1:3 w pm3d notitle
