// boneless-cli inspect TAKE.c3d [--json] [--csv OUT.csv]

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <memory>
#include <nlohmann/json.hpp>
#include <optional>
#include <utility>

#include "Commands.h"
#include "OptionFlags.h"
#include "TakeJob.h"
#include "boneless/Alignment.h"
#include "boneless/C3dReader.h"
#include "boneless/ObjWriter.h"
#include "boneless/OutputFolder.h"
#include "boneless/TakeExport.h"
#include "boneless/TakeOptionsJson.h"
#include "boneless/Text.h"

namespace {

struct InspectOptions {
    std::string take;
    bool json = false;
    std::string csv;
    bool keepZero = false;
    nlohmann::json options = nlohmann::json::object();  // --take-units, as solve reads it
};

// The columns a terminal gives the code point `c`: two for the East Asian wide and fullwidth
// (CJK, Hangul, kana, fullwidth forms, emoji), none for a combining mark, one for the rest.
int columnsOf(char32_t c) {
    if (c >= 0x0300 && c <= 0x036F) return 0;
    static const std::pair<char32_t, char32_t> wide[] = {
        {0x1100, 0x115F},   {0x2E80, 0x303E},  {0x3041, 0x33FF}, {0x3400, 0x4DBF},
        {0x4E00, 0x9FFF},   {0xA000, 0xA4CF},  {0xAC00, 0xD7A3}, {0xF900, 0xFAFF},
        {0xFE30, 0xFE4F},   {0xFF00, 0xFF60},  {0xFFE0, 0xFFE6}, {0x1F300, 0x1F64F},
        {0x1F900, 0x1F9FF}, {0x20000, 0x3FFFD}};
    for (const auto& [first, last] : wide)
        if (c >= first && c <= last) return 2;
    return 1;
}

// `text` (UTF-8) and spaces after it to fill `columns` as a terminal shows them: printf's %-30s
// counts bytes, and a label with a "Ö" or a "頭" shifted the columns after it.
std::string padded(const std::string& text, std::size_t columns) {
    std::size_t width = 0;
    for (std::size_t i = 0; i < text.size();) {
        const std::size_t n = std::max<std::size_t>(1, boneless::utf8SequenceAt(text, i));
        char32_t c = n == 1 ? static_cast<unsigned char>(text[i])
                            : static_cast<unsigned char>(text[i]) & (0x7F >> n);
        for (std::size_t k = 1; k < n; ++k)
            c = (c << 6) | (static_cast<unsigned char>(text[i + k]) & 0x3F);
        width += columnsOf(c);
        i += n;
    }
    return text + std::string(columns > width ? columns - width : 0, ' ');
}

// The number of the last frame the take holds (of one that holds any): a truncated copy's, not
// the header's.
std::int64_t lastFrame(const boneless::C3dTake& t) {
    return t.firstFrame + static_cast<std::int64_t>(t.frameCount()) - 1;
}

// A gap as solve's --frames takes it.
std::string frameRange(const boneless::C3dGap& gap) {
    return std::to_string(gap.first) + ":" + std::to_string(gap.first + gap.frames);
}

// What inspect says of each point's samples.
struct PointGaps {
    std::vector<std::size_t> missing;  // frames missing, per point
    // The longest gap per point (the earliest of equal ones).
    std::vector<boneless::C3dGap> longest;
    std::size_t missingTotal = 0;
    // The longest gap of any marker (the first such marker's): none when no marker has a gap.
    std::optional<std::size_t> longestMarker;
};

PointGaps pointGaps(const boneless::C3dTake& t) {
    PointGaps g;
    const std::vector<std::vector<boneless::C3dGap>> gaps = t.samples.gaps();
    for (std::size_t k = 0; k < t.points.size(); ++k) {
        std::size_t missing = 0;
        boneless::C3dGap longest;
        for (const boneless::C3dGap& gap : gaps[k]) {
            missing += gap.frames;
            if (gap.frames > longest.frames) longest = gap;
        }
        g.missing.push_back(missing);
        g.longest.push_back(longest);
        g.missingTotal += missing;
        if (t.points[k].kind == boneless::C3dPointKind::Marker && longest.frames > 0 &&
            (!g.longestMarker || longest.frames > g.longest[*g.longestMarker].frames))
            g.longestMarker = k;
    }
    return g;
}

// A length of time as a person reads it: "0.083 s", "42.5 s", "25 min 0.0 s".
std::string durationText(double seconds) {
    char text[64];
    if (seconds < 60)
        std::snprintf(text, sizeof text, "%.3g s", seconds);
    else
        std::snprintf(text, sizeof text, "%d min %.1f s", static_cast<int>(seconds / 60),
                      seconds - 60 * std::floor(seconds / 60));
    return text;
}

nlohmann::json gapJson(const boneless::C3dGap& gap) {
    if (gap.frames == 0) return nullptr;
    return {{"frames", gap.frames}, {"frame_range", {gap.first, gap.first + gap.frames}}};
}

nlohmann::json toJson(const boneless::C3dTake& t, const PointGaps& gaps) {
    using boneless::toString;
    nlohmann::json j;
    j["file"] = boneless::validUtf8(t.file);  // a Latin-1 name as the sidecar records it
    j["frame_count"] = t.frameCount();
    j["fps"] =
        t.hasFrameRate() ? nlohmann::json(t.rate) : nlohmann::json(nullptr);  // as the sidecar
    // The frames' count over the rate: null without a rate, as fps.
    j["duration_s"] = t.hasFrameRate() ? nlohmann::json(double(t.frameCount()) / t.rate)
                                       : nlohmann::json(nullptr);
    j["subjects"] = t.subjects();
    j["units"] = t.units;  // the units used: the file's, or --take-units
    // What the file's POINT:UNITS says (null without one), which --take-units may overrule.
    const std::string file = boneless::c3dFileUnits(t);
    j["file_units"] = file.empty() ? nlohmann::json() : nlohmann::json(file);
    j["unit_to_mm"] = t.unitToMm;
    // null without a frame showing 3 markers; a span no body has is also among the warnings.
    const double span = t.markerSpan.mm;
    j["marker_span_mm"] = span > 0 ? nlohmann::json(span) : nlohmann::json();
    j["up_axis"] = boneless::axisName(t.vertical);  // the sidecar's up_axis.take
    j["processor"] = toString(t.processor);
    j["storage"] = toString(t.storage);
    j["scale"] = t.pointScale;
    // The frames held, by their numbers; the header's words apart (a truncated copy's say more).
    j["first_frame"] = t.firstFrame;
    j["last_frame"] = t.frameCount() ? nlohmann::json(lastFrame(t)) : nlohmann::json(nullptr);
    j["header_frames"] = {t.firstFrameWord, t.lastFrameWord};
    j["analog_channels"] = t.analogChannels;
    j["analog_rate"] = t.analogRate;
    j["points"] = nlohmann::json::array();
    for (std::size_t i = 0; i < t.points.size(); ++i) {
        const auto& p = t.points[i];
        j["points"].push_back({{"label", p.label},
                               {"subject", p.subject},
                               {"name", p.name},
                               {"description", p.description},
                               {"kind", toString(p.kind)},
                               {"missing_frames", gaps.missing[i]},
                               {"longest_gap", gapJson(gaps.longest[i])}});
    }
    // The longest gap of any marker, naming it; null when no marker has a gap.
    j["longest_gap"] = nullptr;
    if (gaps.longestMarker) {
        const boneless::C3dGap& gap = gaps.longest[*gaps.longestMarker];
        j["longest_gap"] = gapJson(gap);
        j["longest_gap"]["point"] = *gaps.longestMarker;
        j["longest_gap"]["label"] = t.points[*gaps.longestMarker].label;
        j["longest_gap"]["seconds"] = t.hasFrameRate() ? nlohmann::json(double(gap.frames) / t.rate)
                                                       : nlohmann::json(nullptr);
    }
    j["warnings"] = t.warnings;
    return j;
}

void printSummary(const boneless::C3dTake& t, const PointGaps& gaps, std::ostream& out) {
    using boneless::toString;
    const std::size_t samples = t.frameCount() * t.points.size();
    const std::size_t missing = gaps.missingTotal;
    std::size_t byKind[7] = {};
    for (const auto& p : t.points) ++byKind[static_cast<int>(p.kind)];
    out << t.file << "\n";
    out << "  format    " << toString(t.processor) << ", " << toString(t.storage)
        << " (POINT:SCALE " << t.pointScale << ")\n";
    // No rate is no "@ 0 Hz": the JSON's fps is null, as the sidecar's.
    out << "  frames    " << t.frameCount();
    if (t.hasFrameRate())
        out << " @ " << t.rate << " Hz";
    else
        out << ", no frame rate";
    if (t.frameCount()) out << ", numbered " << t.firstFrame << ".." << lastFrame(t);
    out << " (header frames " << t.firstFrameWord << ".." << t.lastFrameWord << ")\n";
    if (t.hasFrameRate()) {
        const double seconds = double(t.frameCount()) / t.rate;
        char text[32];
        std::snprintf(text, sizeof text, "%.6g s", seconds);
        out << "  duration  " << text;
        if (seconds >= 60) out << " (" << durationText(seconds) << ")";
        out << "\n";
    }
    if (const std::vector<std::string> subjects = t.subjects(); !subjects.empty())
        out << "  subjects  " << boneless::joined(subjects) << "\n";
    out << "  units     " << unitsText(t) << " (x" << t.unitToMm << " to mm)";
    if (const boneless::MarkerSpan& span = t.markerSpan; span.mm > 0)
        out << ", markers span " << boneless::lengthText(span.mm)
            << (span.doubt.empty() ? "" : " (see the warning)");
    out << "\n";
    out << "  up        " << boneless::axisName(t.vertical) << "\n";
    out << "  analog    " << t.analogChannels << " channels @ " << t.analogRate << " Hz\n";
    out << "  points    " << t.points.size();
    const char* sep = " (";
    for (int k = 0; k < 7; ++k) {
        if (!byKind[k]) continue;
        out << sep << byKind[k] << " " << toString(static_cast<boneless::C3dPointKind>(k));
        sep = ", ";
    }
    out << (t.points.empty() ? "" : ")") << "\n";
    char pct[32];
    std::snprintf(pct, sizeof pct, "%.1f",
                  samples ? 100.0 * double(missing) / double(samples) : 0.0);
    out << "  missing   " << missing << " of " << samples << " samples (" << pct << " %)\n";
    // The frames as solve's --frames names them (0-based, the end excluded), to look at or solve.
    if (gaps.longestMarker) {
        const boneless::C3dGap& gap = gaps.longest[*gaps.longestMarker];
        out << "  gaps      longest " << t.points[*gaps.longestMarker].label << ", frames "
            << frameRange(gap) << " (" << boneless::plural(long(gap.frames), "frame");
        if (t.hasFrameRate()) out << ", " << durationText(double(gap.frames) / t.rate);
        out << ")\n";
    }
    for (const auto& w : t.warnings) out << "  warning   " << w << "\n";
    out << "\n  #    label                          kind     missing  longest gap\n";
    for (std::size_t i = 0; i < t.points.size(); ++i) {
        char line[96];
        std::snprintf(line, sizeof line, "  %-4zu ", i);
        out << line << padded(t.points[i].label, 30);
        const boneless::C3dGap& gap = gaps.longest[i];
        std::snprintf(
            line, sizeof line, " %-8s %-8zu %s\n", toString(t.points[i].kind), gaps.missing[i],
            gap.frames ? (std::to_string(gap.frames) + " at " + frameRange(gap)).c_str() : "-");
        out << line;
    }
}

std::string csvField(const std::string& s) {
    if (s.find_first_of(",\"\n\r") == std::string::npos) return s;
    std::string q = "\"";
    for (char c : s) q += (c == '"') ? std::string("\"\"") : std::string(1, c);
    return q + "\"";
}

void writeCsv(const boneless::C3dTake& t, std::ostream& out) {
    std::vector<std::string> labels;
    for (const auto& p : t.points) labels.push_back(csvField(p.label));
    std::string buf = "frame,label,x,y,z,valid\n";
    char num[64];
    auto put = [&](auto v) {
        auto r = std::to_chars(num, num + sizeof num, v);
        buf.append(num, r.ptr);
    };
    for (std::size_t f = 0; f < t.frameCount() && out; ++f) {  // not on past a full disk
        for (std::size_t k = 0; k < t.points.size(); ++k) {
            put(f);
            buf += ',';
            buf += labels[k];
            if (auto p = t.samples.position(f, k)) {
                for (int c = 0; c < 3; ++c) {
                    buf += ',';
                    put((*p)[c]);
                }
                buf += ",1\n";
            } else {
                buf += ",,,,0\n";
            }
        }
        if (buf.size() > (1u << 20)) {
            out.write(buf.data(), std::streamsize(buf.size()));
            buf.clear();
        }
    }
    out.write(buf.data(), std::streamsize(buf.size()));
}

}  // namespace

void registerInspectCommand(CLI::App& app) {
    auto opts = std::make_shared<InspectOptions>();
    CLI::App* cmd = app.add_subcommand(
        "inspect", "Summarise a C3D take: format, frames, rate, units, points and their gaps");
    cmd->add_option("take", opts->take, "C3D file")->required()->check(aPath());
    cmd->add_flag("--json", opts->json, "print one JSON object instead of the summary");
    cmd->add_option("--csv", opts->csv,
                    "write frame,label,x,y,z,valid rows (frame 0-based, file units, empty x/y/z "
                    "where missing)")
        ->check(aPath());
    addOptionFlag(cmd, opts->options, boneless::toJson(boneless::TakeSolveOptions{}), "take_units");
    cmd->add_flag("--keep-zero", opts->keepZero,
                  "keep samples at exactly (0,0,0) instead of treating them as missing");
    cmd->callback([opts]() {
        // `--csv take.c3d` replaced the take with its own CSV.
        if (!opts->csv.empty() && boneless::sameFile(opts->csv, opts->take))
            throw boneless::Error(opts->csv + ": the CSV would replace the take " + opts->take +
                                  "; give --csv another file");
        boneless::C3dReadOptions ro;
        ro.keepZeroSamples = opts->keepZero;
        boneless::C3dTake take = boneless::readC3d(opts->take, ro);
        applyTakeUnits(take, opts->options);
        // Under a temporary name, renamed once whole: a write that fails (a full disk) leaves
        // the file it was to replace as it was. A link or a device (/dev/stdout, a pipe) is
        // written through: a rename would replace the link, or cannot be made beside it.
        std::error_code ec;
        const auto kind = std::filesystem::symlink_status(opts->csv, ec).type();
        if (opts->csv.empty()) {
        } else if (kind == std::filesystem::file_type::not_found ||
                   kind == std::filesystem::file_type::regular) {
            boneless::writeFileAtomically(opts->csv,
                                          [&](std::ostream& out) { writeCsv(take, out); });
        } else {
            std::ofstream out(opts->csv, std::ios::binary);
            if (out) writeCsv(take, out);
            if (!out.flush())
                throw boneless::Error(opts->csv + ": writing failed (" + std::strerror(errno) +
                                      ")");
        }
        const PointGaps gaps = pointGaps(take);
        if (opts->json)
            // Labels are UTF-8 already (the reader converts them); a path need not be.
            std::cout
                << toJson(take, gaps).dump(2, ' ', false, nlohmann::json::error_handler_t::replace)
                << "\n";
        else
            printSummary(take, gaps, std::cout);
    });
}
