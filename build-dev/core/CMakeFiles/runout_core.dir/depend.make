# Empty dependencies file for runout_core.
# This may be replaced when dependencies are built.
