file(REMOVE_RECURSE
  "librunout_core.a"
)
