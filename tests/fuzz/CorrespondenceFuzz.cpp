// libFuzzer target for the correspondence loader. Any text must load or raise Error; what loads
// must write out and load back as the same map.

#include <cstdlib>
#include <string>

#include "FuzzSeeds.h"
#include "boneless/Correspondence.h"
#include "boneless/Error.h"

// Seeds: maps as the writer makes them, one with keys this version does not know.
extern "C" int LLVMFuzzerInitialize(int* argc, char*** argv) {
    const std::string dir = fuzzseeds::seedDir(argc, argv);
    if (dir.empty()) return 0;
    boneless::Correspondence map;
    map.meshFile = "body.obj";
    map.meshVertices = 6;
    fuzzseeds::save(dir, "empty.json", map.toJson());
    map.markers = {{"LFHD", 0, 9.5, "{}"}, {"M\xC3\xBCller:RFHD", 5, 0.0, "{}"}};
    fuzzseeds::save(dir, "two.json", map.toJson());
    map.markers[1].extraJson = R"({"note": [1, {"a": null}], "weight": 2.5})";
    fuzzseeds::save(dir, "extra.json", map.toJson());
    fuzzseeds::done(dir);
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
    using namespace boneless;
    const std::string text(reinterpret_cast<const char*>(data), size);
    Correspondence map;
    try {
        map = Correspondence::fromJson(text, "fuzz.json");
    } catch (const Error&) {
        return 0;
    }
    const Correspondence back = Correspondence::fromJson(map.toJson(), "fuzz-rewritten.json");
    if (back.markers.size() != map.markers.size() || back.meshVertices != map.meshVertices)
        std::abort();
    for (std::size_t i = 0; i < map.markers.size(); ++i)
        if (back.markers[i].label != map.markers[i].label ||
            back.markers[i].vertex != map.markers[i].vertex)
            std::abort();
    return 0;
}
