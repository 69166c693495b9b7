set key noenhanced  # exp_plot: titles are plain names
set xlabel 'BRDF SG lobes n'; set ylabel 'image relative L2 error'; set grid; set key top right;plot 'error_vs_n.dat' u 1:2 w lp t 'sun + sky', '' u 1:3 w lp t '6 lights', '' u 1:4 w lp t '32-lobe SG env'
