# Sourced by the scripts that configure a build folder. Ninja, when installed,
# for new build folders: it starts only the steps a change needs and keeps both
# cores busy (a folder configured before keeps the generator it has).
if command -v ninja >/dev/null; then
  export CMAKE_GENERATOR=${CMAKE_GENERATOR:-Ninja}
fi
