set terminal pngcairo size 1000,560 noenhanced
set output 'validation/results/../figures/sim_curtain.png'
set grid
set key top left
set xlabel 'depth / lambda0'
set ylabel 'crest-count wavelength / lambda0'
set yrange [0:6]
plot 'validation/results/sim_curtain_0.dat' u ($1/10.4):($2/10.4) w l lw 2 t 'case 0: lambda0 10.4 mm, B 1e-06 (L_w 10.9 mm)', 'validation/results/sim_curtain_1.dat' u ($1/6):($2/6) w l lw 2 t 'case 1: lambda0 6.0 mm, B 3.2e-07 (L_w 6.5 mm)', 'validation/results/sim_curtain_2.dat' u ($1/18):($2/18) w l lw 2 t 'case 2: lambda0 18.0 mm, B 3.2e-06 (L_w 18.7 mm)', 'validation/results/sim_curtain_3.dat' u ($1/6):($2/6) w l lw 2 t 'case 3: lambda0 6.0 mm, B 1e-06 (L_w 4.9 mm)', 'validation/results/sim_curtain_4.dat' u ($1/18):($2/18) w l lw 2 t 'case 4: lambda0 18.0 mm, B 1e-06 (L_w 30.1 mm)', 2 w l dt 2 lc rgb 'black' t '2 lambda0'
