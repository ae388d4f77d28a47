// The first section of a C3D file: the header's key, the processor type and the parameters.

#include "C3dTakeLayout.h"

namespace boneless::c3d_detail {

FileStart readFileStart(const Source& src, C3dTake& take) {
    const std::uint8_t* data = src.data;
    const std::size_t size = src.size;
    if (size == 0) src.fail(0, "empty file (0 bytes), not a C3D file");
    if (size < kBlock)
        src.fail(size, "file is " + std::to_string(size) +
                           " bytes, too short for the 512-byte C3D header");
    if (data[1] != 0x50)
        src.fail(1, "not a C3D file: header byte 2 is " + std::to_string(data[1]) +
                        ", the C3D key is 80 (0x50)");

    take.file = src.file;
    auto& warn = take.warnings;

    // The processor type lives in the parameter section, found through the header's pointer
    // (never assumed to be block 2).
    const std::size_t paramBlock = data[0];
    const bool haveParams = paramBlock >= 2 && (paramBlock - 1) * kBlock + 4 <= size;
    const std::size_t paramStart = haveParams ? (paramBlock - 1) * kBlock : 0;
    C3dProcessor proc = C3dProcessor::Intel;
    if (haveParams) {
        const int type = data[paramStart + 3];
        if (type >= 84 && type <= 86) {
            proc = static_cast<C3dProcessor>(type);
        } else {
            proc = guessHeaderProcessor(src);
            warn.push_back("unknown processor type " + std::to_string(type) + " at byte " +
                           std::to_string(paramStart + 3) + "; the header reads as " +
                           toString(proc));
        }
    } else {
        proc = guessHeaderProcessor(src);
        warn.push_back("no parameter section (the header points to block " +
                       std::to_string(paramBlock) + "); using the header only, which reads as " +
                       toString(proc));
    }
    take.processor = proc;
    FileStart start;
    start.processor = proc;
    const HeaderWords& h = start.header = readHeaderWords(src, proc);
    take.firstFrameWord = h.firstFrame;
    take.lastFrameWord = h.lastFrame;

    start.headerDataStart =
        h.dataStartBlock >= 1 ? (std::size_t(h.dataStartBlock) - 1) * kBlock : 0;
    if (haveParams) {
        // Records run to their real end, which may lie past the declared block count, but they
        // cannot run into the 3D data.
        const bool dataAfter = start.headerDataStart > paramStart && start.headerDataStart < size;
        take.parameters =
            readParameterSection(src, paramStart, dataAfter ? start.headerDataStart : size,
                                 dataAfter ? "the start of the 3D data" : "the end of the file",
                                 proc, data[paramStart + 2], warn);
    }
    return start;
}

}  // namespace boneless::c3d_detail
