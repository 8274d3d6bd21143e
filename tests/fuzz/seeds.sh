# The fuzz targets' seeds and settings, for tests/fuzz/smoke and tests/fuzz/run. Sourced; expects SOURCE_DIR, and
# BIN_DIR for the objects of the build (the ELF reader's seeds).

# tree_seeds READER DIR: the tree's own files of READER's format - the labs' rubrics, the corpus's cases, the
# answers files handed out, the build's objects - copied into DIR, which the target reads beside its own seeds
# (tests/fuzz/READER/: the inputs the tree has no file for, and every input a run found a fault with).
tree_seeds() {
  local reader=$1 out=$2 files=() file n=0
  mkdir -p "$out"
  case $reader in
    rubric) mapfile -t files < <(find "$SOURCE_DIR/assignments" "$SOURCE_DIR/examples" -name rubric.toml | sort) ;;
    corpus-case)
      mapfile -t files < <(find "$SOURCE_DIR/tests/corpus" "$SOURCE_DIR/examples" -name '*.toml' -path '*corpus/*' | sort) ;;
    book-answers) files=("$SOURCE_DIR/solutions/book/BookAnswers.toml" "$SOURCE_DIR/starter/book/BookAnswers.toml") ;;
    project-toml) files=("$SOURCE_DIR/solutions/biosim/project.toml" "$SOURCE_DIR/starter/biosim/project.toml") ;;
    elf)
      # The smallest of the build's objects: what compilers make of C++ (the student's objects are the same kind).
      if [[ -n ${BIN_DIR:-} && -d $BIN_DIR/.. ]]; then
        mapfile -t files < <(find "$BIN_DIR/.." -path "$BIN_DIR/../fuzz" -prune -o -name '*.o' -size -48k -printf '%s %p\n' |
                             sort -n | head -n 12 | cut -d' ' -f2-)
      fi ;;
  esac
  for file in "${files[@]}"; do
    [[ -f $file ]] && cp "$file" "$out/tree-$((n++))-$(basename "$file")"
  done
  return 0
}

# fuzz_options READER: libFuzzer's options for READER (its dictionary, where it has one; the longest input).
fuzz_options() {
  local reader=$1 options=(-timeout=20 -rss_limit_mb=2560 -malloc_limit_mb=1024 -print_final_stats=1)
  [[ -f $SOURCE_DIR/tests/fuzz/$reader.dict ]] && options+=("-dict=$SOURCE_DIR/tests/fuzz/$reader.dict")
  case $reader in
    elf) options+=(-max_len=65536) ;;
    corpus-case | answer | record) options+=(-max_len=32768) ;;
    *) options+=(-max_len=8192) ;;
  esac
  printf '%s\n' "${options[@]}"
}

# The targets' scratch folders (the readers that take files and folders) in memory where the machine has a folder
# for it: the intake targets write a download and a class for every input.
if [[ -d /dev/shm && -w /dev/shm ]]; then export TMPDIR=/dev/shm; fi
