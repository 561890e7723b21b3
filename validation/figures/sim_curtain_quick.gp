set terminal pngcairo size 1000,560 noenhanced
set output 'validation/results/../figures/sim_curtain_quick.png'
set grid
set key top left
set xlabel 'depth / lambda0'
set ylabel 'crest-count wavelength / lambda0'
set yrange [0:6]
plot 'validation/results/sim_curtain_quick_0.dat' u ($1/10.4):($2/10.4) w l lw 2 t 'case 0: lambda0 10.4 mm, B 1e-06 (L_w 14.2 mm)', 2 w l dt 2 lc rgb 'black' t '2 lambda0'
