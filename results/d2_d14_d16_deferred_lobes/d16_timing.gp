set key noenhanced  # exp_plot: titles are plain names
set xlabel 'n*m (BRDF lobes x lighting lobes)'; set ylabel 'ns per pixel'; set grid; set key top left;plot for [n in '1 3 7 12'] 'timing.dat' u ($1==n+0?$3:1/0):4 w lp t 'n = '.n, for [n in '1 3 7 12'] 'timing.dat' u ($1==n+0?$3:1/0):5 w l dt 2 lc rgb 'gray' notitle
