t1_t2_t4_t7_color_textures_LDLIBS := -lsquish
