# Sourced by scripts/setup.sh and bench/run_all.sh before they configure a build folder: the
# compiler of a new folder is clang (Debian's clang 14, which setup.sh installs) unless CC or CXX
# already names one. CMake reads CC and CXX only when it makes a folder; an existing folder keeps
# the compiler it was made with.
if [ -z "${CC:-}" ] && [ -z "${CXX:-}" ] && command -v clang >/dev/null &&
  command -v clang++ >/dev/null; then
  export CC=clang CXX=clang++
fi
