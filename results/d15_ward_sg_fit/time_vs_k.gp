set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma; set xlabel 'SG lobes K'; set ylabel 'ms';set logscale y; set grid; set key top left;plot 'error_vs_k.csv' u 1:5 skip 1 w lp t 'mean Ceres time per cell for the K-th fit', 'time_vs_k.csv' u 1:5 skip 1 w lp t 'greedy chain 1..K, reference cell'
