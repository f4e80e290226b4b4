file(REMOVE_RECURSE
  "librunout_render.a"
)
