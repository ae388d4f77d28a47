// The 512-byte header and the parameter section.

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <map>

#include "C3dDetail.h"

namespace boneless::c3d_detail {

HeaderWords readHeaderWords(const Source& src, C3dProcessor proc) {
    const std::uint8_t* d = src.data;
    HeaderWords h;
    h.parameterBlock = d[0];
    h.pointCount = c3d::u16(d + 2, proc);
    h.analogPerFrame = c3d::u16(d + 4, proc);
    h.firstFrame = c3d::u16(d + 6, proc);
    h.lastFrame = c3d::u16(d + 8, proc);
    h.scale = c3d::f32(d + 12, proc);
    h.dataStartBlock = c3d::u16(d + 16, proc);
    h.analogSamplesPerFrame = c3d::u16(d + 18, proc);
    h.rate = c3d::f32(d + 20, proc);
    return h;
}

C3dProcessor guessHeaderProcessor(const Source& src) {
    for (C3dProcessor p : {C3dProcessor::Intel, C3dProcessor::Mips, C3dProcessor::Dec}) {
        const HeaderWords h = readHeaderWords(src, p);
        const bool sane = std::isfinite(h.rate) && h.rate > 0.0f && h.rate < 1e6f &&
                          std::isfinite(h.scale) && h.scale != 0.0f && std::fabs(h.scale) < 1e6f &&
                          h.firstFrame <= h.lastFrame;
        if (sane) return p;
    }
    return C3dProcessor::Intel;
}

namespace {

std::string hexByte(unsigned v) {
    char buf[8];
    std::snprintf(buf, sizeof buf, "0x%02X", v & 0xFFu);
    return buf;
}

// A record the reader can step over when its offset names the next one (an unknown type), or
// one that makes the section unreadable (it runs past the section's end).
struct RecordError {
    std::size_t at;
    std::string cause;
    bool runsPast;  // nothing after it can be reached
};

struct PendingParameter {
    int groupId;
    std::size_t offset;
    C3dParameter parameter;
};

struct PendingGroup {
    C3dGroup group;
    std::size_t offset;
};

class SectionReader {
  public:
    SectionReader(const Source& src, std::size_t limit, const char* limitWhat, C3dProcessor proc)
        : src_(src), limit_(limit), limitWhat_(limitWhat), proc_(proc) {}

    // Fails unless [pos, pos + n) lies inside the section.
    void need(std::size_t record, std::size_t pos, std::size_t n, const char* what) const {
        if (pos > limit_ || n > limit_ - pos)
            throw RecordError{record,
                              std::string("a record's ") + what + " runs past " + limitWhat_ +
                                  " at byte " + std::to_string(limit_),
                              true};
    }

    std::string name(std::size_t record, std::size_t pos, std::size_t n) const {
        std::string s(reinterpret_cast<const char*>(src_.data + pos), n);
        for (std::size_t i = 0; i < n; ++i) {
            const unsigned char c = static_cast<unsigned char>(s[i]);
            // Names are upper-case letters, digits and underscores; printable ASCII is tolerated
            // (lower case, and spaces from Qualisys and BTK), anything else means we are reading
            // garbage.
            if (c < 0x20 || c > 0x7E)
                src_.fail(pos + i, "invalid character " + hexByte(c) +
                                       " in a parameter or group name: the parameter section is "
                                       "corrupt");
        }
        return s;
    }

    C3dParameter values(std::size_t record, std::size_t pos, const std::string& paramName,
                        std::size_t& end) const {
        need(record, pos, 2, "type");
        const int type = static_cast<std::int8_t>(src_.data[pos]);
        const int ndims = src_.data[pos + 1];
        if (type != -1 && type != 1 && type != 2 && type != 4)
            throw RecordError{pos,
                              "parameter " + paramName + " has unknown type " +
                                  std::to_string(type) + " (expected -1, 1, 2 or 4)",
                              false};
        if (ndims > 7)
            throw RecordError{pos + 1,
                              "parameter " + paramName + " has " + std::to_string(ndims) +
                                  " dimensions (at most 7)",
                              false};
        need(record, pos + 2, std::size_t(ndims), "dimensions");
        std::vector<int> dims;
        std::size_t count = 1;  // at most 255^7, fits in 64 bits
        for (int i = 0; i < ndims; ++i) {
            dims.push_back(src_.data[pos + 2 + i]);
            count *= std::size_t(dims.back());
        }
        const std::size_t elem = static_cast<std::size_t>(std::abs(type));
        const std::size_t dataPos = pos + 2 + std::size_t(ndims);
        if (count > (limit_ - std::min(limit_, dataPos)) / elem)
            throw RecordError{record,
                              "the values of parameter " + paramName + " (" +
                                  std::to_string(count * elem) + " bytes) run past " + limitWhat_ +
                                  " at byte " + std::to_string(limit_),
                              true};
        const std::uint8_t* d = src_.data + dataPos;
        std::vector<std::uint8_t> bytes;
        std::vector<std::int16_t> ints;
        std::vector<float> floats;
        if (type == 2) {
            ints.resize(count);
            for (std::size_t i = 0; i < count; ++i) ints[i] = c3d::i16(d + 2 * i, proc_);
        } else if (type == 4) {
            floats.resize(count);
            for (std::size_t i = 0; i < count; ++i) floats[i] = c3d::f32(d + 4 * i, proc_);
        } else {
            bytes.assign(d, d + count);
        }
        C3dParameter p;
        p.name = paramName;
        p.assign(static_cast<C3dParamType>(type), std::move(dims), std::move(bytes),
                 std::move(ints), std::move(floats));
        end = dataPos + count * elem;
        return p;
    }

    std::string description(std::size_t record, std::size_t pos, std::size_t& end) const {
        need(record, pos, 1, "description length");
        const std::size_t n = src_.data[pos];
        need(record, pos + 1, n, "description");
        end = pos + 1 + n;
        std::string s(reinterpret_cast<const char*>(src_.data + pos + 1), n);
        while (!s.empty() && (s.back() == ' ' || s.back() == '\0')) s.pop_back();
        return s;
    }

  private:
    const Source& src_;
    std::size_t limit_;
    const char* limitWhat_;
    C3dProcessor proc_;
};

}  // namespace

C3dParameters readParameterSection(const Source& src, std::size_t start, std::size_t limit,
                                   const char* limitWhat, C3dProcessor proc, int declaredBlocks,
                                   std::vector<std::string>& warnings) {
    SectionReader in(src, limit, limitWhat, proc);
    std::vector<PendingGroup> groups;
    std::map<int, std::size_t> groupById;
    std::vector<PendingParameter> parameters;
    std::size_t pos = start + 4;
    std::size_t furthest = pos;
    while (pos + 2 <= limit) {
        const std::size_t record = pos;
        const int nameLen = static_cast<std::int8_t>(src.data[pos]);
        if (nameLen == 0) break;  // zero padding after the last record
        const int id = static_cast<std::int8_t>(src.data[pos + 1]);
        const std::size_t n = static_cast<std::size_t>(std::abs(nameLen));
        if (pos + 2 + n + 2 > limit)
            src.fail(record, "corrupt parameter section: a record's name runs past " +
                                 std::string(limitWhat) + " at byte " + std::to_string(limit));
        const std::string name = in.name(record, pos + 2, n);
        const std::size_t offsetPos = pos + 2 + n;
        const int offset = c3d::i16(src.data + offsetPos, proc);
        if (offset < 0)
            src.fail(offsetPos, "record " + name + " gives a negative offset (" +
                                    std::to_string(offset) +
                                    ") to the next record: the parameter section is corrupt");
        if (id == 0) {  // belongs to no group: step over it
            warnings.push_back("parameter section: record " + name + " at byte " +
                               std::to_string(record) + " has group id 0; ignored");
            if (offset == 0) break;
            pos = offsetPos + std::size_t(offset);
            continue;
        }
        const std::size_t body = offsetPos + 2;
        std::size_t end = body;
        try {
            if (id < 0) {
                PendingGroup g;
                g.group.name = name;
                g.group.locked = nameLen < 0;
                g.offset = record;
                // Some writers leave out the description of a group; an offset of 2 says so.
                if (offset == 0 || body < offsetPos + std::size_t(offset))
                    g.group.description = in.description(record, body, end);
                if (groupById.count(-id)) {
                    warnings.push_back("parameter section: group id " + std::to_string(-id) +
                                       " is defined twice (" + groups[groupById[-id]].group.name +
                                       ", " + name + "); the second is ignored");
                } else {
                    groupById[-id] = groups.size();
                    groups.push_back(std::move(g));
                }
            } else {
                std::size_t dataEnd = body;
                C3dParameter p = in.values(record, body, name, dataEnd);
                p.locked = nameLen < 0;
                p.fileOffset = static_cast<std::int64_t>(record);
                end = dataEnd;
                if (offset != 0 && offsetPos + std::size_t(offset) < dataEnd)
                    src.fail(offsetPos,
                             "parameter " + name + "'s offset to the next record (" +
                                 std::to_string(offset) +
                                 ") points inside its own values: the parameter section is "
                                 "corrupt");
                if (offset == 0 || dataEnd < offsetPos + std::size_t(offset))
                    p.description = in.description(record, dataEnd, end);
                parameters.push_back(PendingParameter{id, record, std::move(p)});
            }
        } catch (const RecordError& e) {
            if (e.runsPast || offset == 0) src.fail(e.at, "corrupt parameter section: " + e.cause);
            warnings.push_back("parameter section: " + e.cause + "; the record is ignored");
            pos = offsetPos + std::size_t(offset);
            continue;
        }
        furthest = std::max(furthest, end);
        if (offset == 0) break;  // the last record says so
        pos = offsetPos + std::size_t(offset);
    }

    const std::size_t declaredEnd = start + std::size_t(declaredBlocks) * kBlock;
    if (declaredBlocks > 0 && furthest > declaredEnd)
        warnings.push_back("parameter section declares " + std::to_string(declaredBlocks) +
                           " blocks but its records run to byte " + std::to_string(furthest) +
                           "; all records were read");

    C3dParameters out;
    for (auto& g : groups) {
        if (out.group(g.group.name)) {
            warnings.push_back("parameter section: group " + g.group.name +
                               " appears twice; parameters merged");
            continue;
        }
        C3dGroup& dst = out.addGroup(g.group.name, g.group.description);
        dst.locked = g.group.locked;
    }
    std::size_t orphans = 0;
    for (auto& p : parameters) {
        auto it = groupById.find(p.groupId);
        if (it == groupById.end()) {
            ++orphans;
            continue;
        }
        C3dGroup* g = out.group(groups[it->second].group.name);
        if (g->find(p.parameter.name)) {
            warnings.push_back("parameter " + g->name + ":" + p.parameter.name +
                               " appears twice; the first is kept");
            continue;
        }
        g->parameters.push_back(std::move(p.parameter));
    }
    if (orphans > 0)
        warnings.push_back(std::to_string(orphans) +
                           " parameters belong to no defined group and were ignored");
    return out;
}

}  // namespace boneless::c3d_detail
