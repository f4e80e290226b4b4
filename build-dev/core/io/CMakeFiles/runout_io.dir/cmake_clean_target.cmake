file(REMOVE_RECURSE
  "librunout_io.a"
)
