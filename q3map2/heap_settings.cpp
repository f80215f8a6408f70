// The executable's allocator settings. The compiler links jemalloc (outside sanitizer builds, whose
// runtime brings its own allocator) and configures it here, at build time, through the
// `malloc_conf` string jemalloc reads when it starts.
//
// thp:always asks the kernel for 2 MiB pages on jemalloc's memory. Debian's default THP mode is
// "madvise", so without the advice every 4 KiB page of a luxel, sample or tree array is a page
// fault of its own: on a small map that was 12 % of -light's CPU time, most of it spent in the
// hypervisor's fault path (docs/light-speed-log.md, "The allocator"). metadata_thp does the same
// for jemalloc's own tables. percpu_arena keeps one arena per core, which bounds the memory that
// per-thread arenas would add on machines with many threads.
extern "C" {
// Read by jemalloc's initialisation; the name and the type are jemalloc's interface.
extern const char* const malloc_conf;
const char* const malloc_conf = "thp:always,metadata_thp:always,percpu_arena:percpu";
}
