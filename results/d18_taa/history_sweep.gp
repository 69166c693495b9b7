set key noenhanced  # exp_plot: titles are plain names
set logscale x 2; set xlabel 'history cap (frames)'; set ylabel 'far-region RMS error (panning camera)';set grid; set key top left;plot 'history_sweep.dat' u 1:2 w lp t 'TAA, bilinear history', '' u 1:3 w lp t 'TAA, Catmull-Rom history', '' u 1:4 w l dt 2 t 'aliased'
