#pragma once

// The sections of readTakeLayout (C3dReader.cpp), in the order it calls them. The header and the
// parameter section both describe the data: each section trusts the parameters, falls back on the
// header when they are unusable and says so in the take's warnings.

#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "C3dDetail.h"

namespace boneless::c3d_detail {

std::optional<double> paramNumber(const C3dParameters& ps, const char* group, const char* name,
                                  bool unsignedInt16 = true);
// A count from the parameters that is not a whole number in [0, max] (NaN, negative, 1e30) is
// ignored in favour of the header's, with a warning.
std::size_t countOr(std::vector<std::string>& warn, double v, double max, const std::string& what,
                    std::size_t fallback);

struct FileStart {
    C3dProcessor processor = C3dProcessor::Intel;
    HeaderWords header;
    std::size_t headerDataStart = 0;  // byte offset of frame 0 by the header; 0 when unset
};
// Checks the C3D key, finds the processor and reads the header and the parameter section:
// fills take.file, processor, firstFrameWord, lastFrameWord and parameters.
FileStart readFileStart(const Source& src, C3dTake& take);

// C3dPointSettings.cpp
std::size_t pointCount(const C3dParameters& ps, const HeaderWords& h,
                       std::vector<std::string>& warn);
// Its sign selects int16 (> 0) or float (< 0) storage; may still be 0 or NaN (chooseStorage).
double pointScale(const C3dParameters& ps, const HeaderWords& h, std::vector<std::string>& warn);
// Frames per second, 0 when neither the header nor POINT:RATE gives a usable one.
double frameRate(const C3dParameters& ps, const HeaderWords& h, std::vector<std::string>& warn);
// take.units and take.unitToMm from POINT:UNITS; latin1 is set when the text was not UTF-8.
void readUnits(const C3dParameters& ps, C3dTake& take, bool& latin1);

// C3dAnalogAndFrames.cpp
struct AnalogFrame {
    std::size_t channels = 0;
    std::size_t samplesPerFrame = 0;
    std::size_t words() const { return channels * samplesPerFrame; }
};
// The analog channels interleaved in each frame; fills take.analogChannels, analogRate and
// analogSamplesPerFrame.
AnalogFrame readAnalog(const C3dParameters& ps, const HeaderWords& h, double rate, C3dTake& take);
// The frames the file declares (before checking the file holds them); fills take.firstFrame.
std::size_t declaredFrameCount(const C3dParameters& ps, const HeaderWords& h, C3dTake& take);

// C3dFramePlacement.cpp: where the frames lie and how they are stored. L.points and
// L.analogWords are set before these run.
void chooseStorage(const Source& src, const HeaderWords& h, double scale, PointLayout& L,
                   C3dTake& take);
std::size_t chooseDataStart(const Source& src, const C3dParameters& ps, const HeaderWords& h,
                            std::size_t headerDataStart, const PointLayout& L,
                            std::vector<std::string>& warn);
// After chooseDataStart: the header's storage when POINT:SCALE's does not fit the file and it does.
void reconcileStorage(const Source& src, const HeaderWords& h, std::size_t declaredFrames,
                      PointLayout& L, C3dTake& take);
void reconcileAnalogWords(const Source& src, const HeaderWords& h, const AnalogFrame& analog,
                          std::size_t declaredFrames, PointLayout& L,
                          std::vector<std::string>& warn);
// Sets L.frames to the declared frames the file holds completely.
void keepCompleteFrames(const Source& src, std::size_t declaredFrames, PointLayout& L,
                        std::vector<std::string>& warn);

// C3dLabels.cpp: take.points, named from POINT:LABELS (LABELS2, ...) and DESCRIPTIONS.
void readLabels(const C3dParameters& ps, std::size_t points, C3dTake& take, bool& latin1);

}  // namespace boneless::c3d_detail
