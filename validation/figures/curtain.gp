set terminal pngcairo size 900,500
set output 'validation/results/../figures/curtain.png'
set grid
set xlabel 'depth below the gathered top edge [mm]'
set ylabel 'wavelength [mm]'
set yrange [0:40]
plot 'validation/results/curtain_0.dat' u 1:2 w l lw 2 t 'B = 1e-06 (L_w pred. 34.3 mm)', 'validation/results/curtain_1.dat' u 1:2 w l lw 2 t 'B = 2e-06 (L_w pred. 24.3 mm)', 'validation/results/curtain_2.dat' u 1:2 w l lw 2 t 'B = 4e-06 (L_w pred. 17.2 mm)', 20 w l dt 2 t '2 lambda0'
