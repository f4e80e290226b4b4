# Empty dependencies file for runout_io.
# This may be replaced when dependencies are built.
