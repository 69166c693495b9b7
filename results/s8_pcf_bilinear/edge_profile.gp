set key noenhanced  # exp_plot: titles are plain names
set datafile separator comma
set xlabel 'distance across an axis-aligned shadow edge (texels)'
set ylabel 'filtered lit fraction'
set key top left
set grid
plot 'edge_profile.csv' every ::1 using 1:2 with lines lw 2 title '3x3 weighted box', '' every ::1 using 1:3 with lines lw 2 dt 2 title '4 bilinear taps (Tesseract)', '' every ::1 using 1:($3-$2) with lines title 'difference'

