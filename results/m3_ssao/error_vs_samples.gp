set key noenhanced  # exp_plot: titles are plain names
set datafile columnheaders  # exp_plot: each CSV block starts with a header line
set datafile separator comma
set logscale xy
set xlabel 'samples per pixel (accumulated curves: 4 x frame number)'
set ylabel 'RMS error of VO'
set grid
set key bottom left
set xtics (4,8,16,32,64,128)
plot 'samples_curves.csv' using 1:2 with linespoints lw 2 title 'full resolution', '' using 1:4 with linespoints title 'half resolution + bilateral upsampling', 'temporal_curves.csv' using ($1*4):2 with lines dt 2 title '4 samples x frames, still camera', '' using ($1*4):3 with linespoints dt 3 title '4 samples, moving, no accumulation', '' using ($1*4):5 with linespoints dt 4 title '4 samples x frames, moving, cap 8', '' using ($1*4):7 with linespoints dt 5 title '4 samples x frames, moving, cap 32'
