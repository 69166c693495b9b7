set key noenhanced  # exp_plot: titles are plain names
set logscale xy; set xlabel 'microseconds per integral'; set ylabel 'absolute error';set grid; set key top right;plot 'quadrature.dat' u ($1==0?$2:1/0):3 w lp t 'adaptive Gauss-Kronrod', '' u ($1==1?$2:1/0):3 w lp t 'stratified Monte Carlo'
