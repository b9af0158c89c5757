// BenchInputs: the benchmarks' inputs (BenchInputs.h) for programs that cannot link the
// harness, such as BenchCUDBConnectivity.py: one definition of the inputs for all.
//
//   BenchInputs [the input options of the benchmarks] --list     one line per input
//   BenchInputs [the input options of the benchmarks] --emit NAME
//
// --emit writes the line "nx ny nz" then the selection of that input as nx*ny*nz bytes 0/1,
// x fastest, to stdout.
#include "BenchCommon.h"

#include <cstdio>
#include <cstring>
#include <string>
#include <vector>

int main(int argc, char* argv[])
{
  std::string emit;
  std::vector<char*> args;
  for (int i = 0; i < argc; ++i)
    if (std::strcmp(argv[i], "--emit") == 0 && i + 1 < argc)
      emit = argv[++i];
    else
      args.push_back(argv[i]);
  vbrbench::Options options;
  options.inputs.classes = { "all" };
  const int stop = vbrbench::parseOptions(static_cast<int>(args.size()),
    args.data(),
    "BenchInputs: the benchmarks' inputs, listed (--list) or written (--emit NAME)",
    options);
  if (stop >= 0)
    return stop;
  for (const vbrbench::InputSpec& spec : vbrbench::selectInputs(options.inputs))
  {
    vbrbench::Input in;
    if (spec.name != emit || !vbrbench::loadInput(spec, in))
      continue;
    std::vector<unsigned char> mask(in.voxelCount());
    for (std::size_t i = 0; i < mask.size(); ++i)
      mask[i] = in.selected(i);
    std::printf("%d %d %d\n", in.dims[0], in.dims[1], in.dims[2]);
    std::fwrite(mask.data(), 1, mask.size(), stdout);
    return 0;
  }
  std::fprintf(stderr, "no input named '%s' (see --list)\n", emit.c_str());
  return 1;
}
