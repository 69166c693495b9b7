t8_t14_3dc_encoders_LDLIBS := -lsquish -lnvtt
