file(REMOVE_RECURSE
  "CMakeFiles/runout_pictures.dir/picture_options.cpp.o"
  "CMakeFiles/runout_pictures.dir/picture_options.cpp.o.d"
  "CMakeFiles/runout_pictures.dir/render_cli.cpp.o"
  "CMakeFiles/runout_pictures.dir/render_cli.cpp.o.d"
  "runout_pictures.pdb"
  "runout_pictures.so"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/runout_pictures.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
