# Empty dependencies file for runout_pictures.
# This may be replaced when dependencies are built.
