set terminal pngcairo size 1000,520
set output 'validation/results/../figures/curtain.png'
set grid
set key bottom right
set xlabel 'depth below the gathered top edge [mm]'
set ylabel 'crest-count wavelength [mm]'
set xrange [0:80]
set yrange [0:60]
plot 'validation/results/curtain_0.dat' u 1:6 w l lw 2 lc 1 t 'B = 1e-06, rho_A = 0.15: 2 lambda0 at 9.4 mm (L_w tension 34.3, compression 30.0)', 'validation/results/curtain_1.dat' u 1:6 w l lw 2 lc 2 t 'B = 2e-06, rho_A = 0.15: 2 lambda0 at 7.1 mm (L_w tension 24.3, compression 26.7)', 'validation/results/curtain_2.dat' u 1:6 w l lw 2 lc 3 t 'B = 4e-06, rho_A = 0.15: 2 lambda0 at 6.0 mm (L_w tension 17.2, compression 23.8)', 'validation/results/curtain_3.dat' u 1:6 w l lw 2 lc 4 t 'B = 2e-06, rho_A = 0.60: 2 lambda0 at 6.9 mm (L_w tension 48.5, compression 26.7)', 'validation/results/curtain_4.dat' u 1:6 w l lw 2 lc 5 t 'B = 2e-06, rho_A = 2.50: 2 lambda0 at 11.5 mm (L_w tension 156.6, compression 26.7)', 20 w l dt 2 lc rgb 'black' t '2 lambda0'
