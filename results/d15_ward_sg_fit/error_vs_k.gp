set key noenhanced  # exp_plot: titles are plain names
set logscale y; set xlabel 'SG lobes K'; set ylabel 'relative L2 error of the NDF';set key bottom left; set grid;plot 'curves.dat' u 1:2 w lp t 'ax 0.04, ay 0.04', '' u 1:3 w lp t 'ax 0.04, ay 0.80', '' u 1:4 w lp t 'ax 0.09, ay 0.34', '' u 1:5 w lp t 'ax 0.80, ay 0.80', 0.02 w l dt 2 lc rgb 'black' t '2% level'
