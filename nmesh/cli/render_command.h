// nmesh/cli/render_command.h — `nmesh render`: draw a mesh to a PNG image.
#pragma once

namespace nmesh::cli {

// Runs `nmesh render MESH -o IMAGE.png [options]`: argv[1] is "render", the options start at
// argv[2]. Prints the usage to stdout and returns 0 for --help or -h. Returns 0 on success.
// Throws UsageError for bad arguments and nmesh::Error (IoError, ...) for files that cannot be
// read or written; the caller turns them into exit statuses 2 and 1.
int run_render(int argc, char** argv);

}  // namespace nmesh::cli
