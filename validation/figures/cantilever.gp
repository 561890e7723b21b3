set terminal pngcairo size 800,500
set output 'validation/results/../figures/cantilever.png'
set logscale xy
set xlabel 'mesh resolution r [mm]'
set ylabel '|error| [%]'
set grid
set key top left
set arrow from 6.4578, graph 0 to 6.4578, graph 1 nohead dt 2
plot 'validation/results/cantilever.dat' i 0 u 1:(abs($2)) w lp t 'tip vs elastica, L = 100 mm', 'validation/results/cantilever.dat' i 0 u 1:3 w lp t 'shape error / L, L = 100 mm', 'validation/results/cantilever.dat' i 1 u 1:(abs($2)) w lp t 'tip vs elastica, L = 25 mm'
