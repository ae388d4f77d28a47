#include "boneless/C3dTake.h"

#include <algorithm>
#include <limits>
#include <map>
#include <stdexcept>

#include "boneless/Text.h"

namespace boneless {

const char* toString(C3dProcessor processor) {
    switch (processor) {
        case C3dProcessor::Dec:
            return "dec";
        case C3dProcessor::Mips:
            return "mips";
        case C3dProcessor::Intel:
        default:
            return "intel";
    }
}

const char* toString(C3dStorage storage) {
    return storage == C3dStorage::Int16 ? "int16" : "float";
}

const char* toString(C3dPointKind kind) {
    switch (kind) {
        case C3dPointKind::Angle:
            return "angle";
        case C3dPointKind::Force:
            return "force";
        case C3dPointKind::Moment:
            return "moment";
        case C3dPointKind::Power:
            return "power";
        case C3dPointKind::Scalar:
            return "scalar";
        case C3dPointKind::Virtual:
            return "virtual";
        case C3dPointKind::Marker:
        default:
            return "marker";
    }
}

namespace {
// frames x points, refusing sizes whose coordinate block (x3) would overflow before any vector
// is sized from them.
std::size_t sampleCount(std::size_t frames, std::size_t points) {
    if (points != 0 && frames > std::numeric_limits<std::size_t>::max() / 3 / points)
        throw std::length_error("C3dSamples: frames x points overflows");
    return frames * points;
}
}  // namespace

C3dSamples::C3dSamples(std::size_t frames, std::size_t points, Precision precision)
    : frames_(frames), points_(points), block_(std::make_shared<Block>()) {
    const std::size_t n = 3 * sampleCount(frames, points);
    if (precision == Precision::Double)
        block_->wide.assign(n, std::numeric_limits<double>::quiet_NaN());
    else
        block_->xyz.assign(n, std::numeric_limits<float>::quiet_NaN());
}

void C3dSamples::setMissingAt(std::size_t i) {
    Block& b = own();
    if (b.wide.empty())
        b.xyz[3 * i] = b.xyz[3 * i + 1] = b.xyz[3 * i + 2] =
            std::numeric_limits<float>::quiet_NaN();
    else
        b.wide[3 * i] = b.wide[3 * i + 1] = b.wide[3 * i + 2] =
            std::numeric_limits<double>::quiet_NaN();
}

void C3dSamples::check(std::size_t frame, std::size_t point) const {
    if (frame >= frames_ || point >= points_)
        throw std::out_of_range("C3dSamples: sample (" + std::to_string(frame) + ", " +
                                std::to_string(point) + ") outside " + std::to_string(frames_) +
                                " x " + std::to_string(points_));
}

bool C3dSamples::valid(std::size_t frame, std::size_t point) const {
    check(frame, point);
    return validAt(frame * points_ + point);
}

std::optional<Eigen::Vector3d> C3dSamples::position(std::size_t frame, std::size_t point) const {
    check(frame, point);
    const std::size_t i = frame * points_ + point;
    if (!validAt(i)) return std::nullopt;
    return at(i);
}

float C3dSamples::residual(std::size_t frame, std::size_t point) const {
    check(frame, point);
    const std::size_t i = frame * points_ + point;
    if (!validAt(i)) return -1.0f;
    return block_->residual.empty() ? 0.0f : block_->residual[i];
}

std::size_t C3dSamples::missingFrames(std::size_t point) const {
    if (point >= points_) throw std::out_of_range("C3dSamples: point index out of range");
    std::size_t n = 0;
    for (std::size_t f = 0; f < frames_; ++f) n += validAt(f * points_ + point) ? 0 : 1;
    return n;
}

std::size_t C3dSamples::missingCount() const {
    std::size_t n = 0;
    for (std::size_t i = 0; i < frames_ * points_; ++i) n += validAt(i) ? 0 : 1;
    return n;
}

std::vector<std::vector<C3dGap>> C3dSamples::gaps() const {
    std::vector<std::vector<C3dGap>> out(points_);
    for (std::size_t f = 0; f < frames_; ++f)
        for (std::size_t k = 0; k < points_; ++k) {
            if (validAt(f * points_ + k)) continue;
            std::vector<C3dGap>& runs = out[k];
            if (!runs.empty() && runs.back().first + runs.back().frames == f)
                ++runs.back().frames;
            else
                runs.push_back({f, 1});
        }
    return out;
}

bool C3dSamples::samePositions(const C3dSamples& other) const {
    if (frames_ != other.frames_ || points_ != other.points_) return false;
    if (sharesData(other) || frames_ * points_ == 0) return true;
    for (std::size_t i = 0; i < frames_ * points_; ++i) {
        const bool seen = validAt(i);
        if (seen != other.validAt(i) || (seen && at(i) != other.at(i))) return false;
    }
    return true;
}

std::size_t C3dSamples::bytes() const {
    if (!block_) return 0;
    return sizeof(Block) + block_->xyz.capacity() * sizeof(float) +
           block_->wide.capacity() * sizeof(double) + block_->residual.capacity() * sizeof(float);
}

void splitC3dLabel(std::string_view label, std::string& subject, std::string& name) {
    const std::size_t colon = label.find(':');
    if (colon == std::string_view::npos) {
        subject.clear();
        name = std::string(label);
        return;
    }
    subject = std::string(label.substr(0, colon));
    name = std::string(label.substr(colon + 1));
}

namespace {
std::string_view trimView(std::string_view s) {
    while (!s.empty() && (s.front() == ' ' || s.front() == '\t')) s.remove_prefix(1);
    while (!s.empty() && (s.back() == ' ' || s.back() == '\t' || s.back() == '\0'))
        s.remove_suffix(1);
    return s;
}
}  // namespace

std::vector<std::size_t> C3dTake::pointsNamed(std::string_view label) const {
    label = trimView(label);
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (c3dNameEquals(trimView(points[i].label), label)) out.push_back(i);
    if (!out.empty()) return out;
    // The caller may give "subject:NAME" for a file without prefixes, or "NAME" for one with;
    // a prefix names its subject, and finds no other subject's NAME ("other:T10" bound
    // walker:T10).
    std::string subject, name;
    splitC3dLabel(label, subject, name);
    for (std::size_t i = 0; i < points.size(); ++i)
        if (c3dNameEquals(trimView(points[i].name), trimView(name)) &&
            (subject.empty() || points[i].subject.empty() ||
             c3dNameEquals(trimView(points[i].subject), trimView(subject))))
            out.push_back(i);
    return out;
}

std::string C3dTake::rateText() const {
    if (std::isnan(rate)) return "not a number";
    return shortNumber(rate) + " Hz";
}

std::vector<std::vector<std::size_t>> C3dTake::sharedLabels() const {
    // Keyed as c3dNameEquals compares: ASCII letters in upper case. A map, since a take may hold
    // 65535 points.
    std::map<std::string, std::vector<std::size_t>> byLabel;
    for (std::size_t i = 0; i < points.size(); ++i) {
        std::string key(trimView(points[i].label));
        for (char& c : key)
            if (c >= 'a' && c <= 'z') c = char(c - 'a' + 'A');
        byLabel[key].push_back(i);
    }
    std::vector<std::vector<std::size_t>> shared;
    for (auto& [key, group] : byLabel)
        if (group.size() > 1) shared.push_back(std::move(group));
    std::sort(shared.begin(), shared.end());
    return shared;
}

std::string C3dTake::sharedLabelText(const std::vector<std::size_t>& group) const {
    constexpr std::size_t kListed = 5;
    std::vector<std::string> listed;
    for (std::size_t k = 0; k < group.size() && k < kListed; ++k)
        listed.push_back(std::to_string(group[k]));
    if (group.size() > kListed) listed.push_back(std::to_string(group.size() - kListed) + " more");
    std::string text = "points ";
    for (std::size_t k = 0; k < listed.size(); ++k)
        text += (k == 0 ? "" : k + 1 == listed.size() ? " and " : ", ") + listed[k];
    return text + (group.size() == 2 ? " are both labelled " : " are all labelled ") +
           points.at(group.front()).label;
}

std::vector<std::string> C3dTake::subjects() const {
    std::vector<std::string> out;
    for (const C3dPoint& p : points)
        if (!p.subject.empty() && std::none_of(out.begin(), out.end(), [&](const std::string& s) {
                return c3dNameEquals(s, p.subject);
            }))
            out.push_back(p.subject);
    return out;
}

std::optional<std::size_t> C3dTake::findPoint(std::string_view label) const {
    const std::vector<std::size_t> named = pointsNamed(label);
    if (named.size() != 1) return std::nullopt;
    return named.front();
}

std::string C3dTake::shortLabel(std::size_t point) const {
    const C3dPoint& p = points.at(point);
    return !p.name.empty() && findPoint(p.name) == point ? p.name : p.label;
}

std::vector<std::size_t> C3dTake::markerIndices() const {
    std::vector<std::size_t> out;
    for (std::size_t i = 0; i < points.size(); ++i)
        if (points[i].kind == C3dPointKind::Marker) out.push_back(i);
    return out;
}

}  // namespace boneless
