file(REMOVE_RECURSE
  "CMakeFiles/runout_render.dir/src/colormap.cpp.o"
  "CMakeFiles/runout_render.dir/src/colormap.cpp.o.d"
  "CMakeFiles/runout_render.dir/src/frame.cpp.o"
  "CMakeFiles/runout_render.dir/src/frame.cpp.o.d"
  "CMakeFiles/runout_render.dir/src/gl_renderer.cpp.o"
  "CMakeFiles/runout_render.dir/src/gl_renderer.cpp.o.d"
  "CMakeFiles/runout_render.dir/src/image.cpp.o"
  "CMakeFiles/runout_render.dir/src/image.cpp.o.d"
  "CMakeFiles/runout_render.dir/src/recorders.cpp.o"
  "CMakeFiles/runout_render.dir/src/recorders.cpp.o.d"
  "CMakeFiles/runout_render.dir/src/text.cpp.o"
  "CMakeFiles/runout_render.dir/src/text.cpp.o.d"
  "CMakeFiles/runout_render.dir/src/video.cpp.o"
  "CMakeFiles/runout_render.dir/src/video.cpp.o.d"
  "librunout_render.a"
  "librunout_render.pdb"
)

# Per-language clean rules from dependency scanning.
foreach(lang CXX)
  include(CMakeFiles/runout_render.dir/cmake_clean_${lang}.cmake OPTIONAL)
endforeach()
