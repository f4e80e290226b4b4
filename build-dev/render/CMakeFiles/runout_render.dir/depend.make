# Empty dependencies file for runout_render.
# This may be replaced when dependencies are built.
