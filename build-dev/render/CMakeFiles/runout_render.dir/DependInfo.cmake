
# Consider dependencies only in project.
set(CMAKE_DEPENDS_IN_PROJECT_ONLY OFF)

# The set of languages for which implicit dependencies are needed:
set(CMAKE_DEPENDS_LANGUAGES
  )

# The set of dependency files which are needed:
set(CMAKE_DEPENDS_DEPENDENCY_FILES
  "/work/main/render/src/colormap.cpp" "render/CMakeFiles/runout_render.dir/src/colormap.cpp.o" "gcc" "render/CMakeFiles/runout_render.dir/src/colormap.cpp.o.d"
  "/work/main/render/src/frame.cpp" "render/CMakeFiles/runout_render.dir/src/frame.cpp.o" "gcc" "render/CMakeFiles/runout_render.dir/src/frame.cpp.o.d"
  "/work/main/render/src/gl_renderer.cpp" "render/CMakeFiles/runout_render.dir/src/gl_renderer.cpp.o" "gcc" "render/CMakeFiles/runout_render.dir/src/gl_renderer.cpp.o.d"
  "/work/main/render/src/image.cpp" "render/CMakeFiles/runout_render.dir/src/image.cpp.o" "gcc" "render/CMakeFiles/runout_render.dir/src/image.cpp.o.d"
  "/work/main/render/src/recorders.cpp" "render/CMakeFiles/runout_render.dir/src/recorders.cpp.o" "gcc" "render/CMakeFiles/runout_render.dir/src/recorders.cpp.o.d"
  "/work/main/render/src/text.cpp" "render/CMakeFiles/runout_render.dir/src/text.cpp.o" "gcc" "render/CMakeFiles/runout_render.dir/src/text.cpp.o.d"
  "/work/main/render/src/video.cpp" "render/CMakeFiles/runout_render.dir/src/video.cpp.o" "gcc" "render/CMakeFiles/runout_render.dir/src/video.cpp.o.d"
  )

# Targets to which this target links.
set(CMAKE_TARGET_LINKED_INFO_FILES
  "/work/main/build-dev/core/CMakeFiles/runout_core.dir/DependInfo.cmake"
  "/work/main/build-dev/core/io/CMakeFiles/runout_io.dir/DependInfo.cmake"
  )

# Fortran module output directory.
set(CMAKE_Fortran_TARGET_MODULE_DIR "")
