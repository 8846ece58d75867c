// streetgen-osm-stage: reads an OSM file (.osm, .osm.gz, .osm.bz2, .pbf) with libosmium and
// writes, in PostgreSQL's COPY text format, what streetgen's import stages from it:
//
//   kind   'way'     every way with a highway tag, as a LineString
//          'parking' street parking mapped as its own area (amenity=parking with parking =
//                    street_side | lane | layby): a closed way that is not a highway, or a
//                    type=multipolygon relation, as a (Multi)Polygon
//   source 'osm:way/<id>' or 'osm:relation/<id>'
//   tags   every tag of the object, a JSON object
//   geom   hex EWKB in WGS 84 (SRID 4326)
//
//   streetgen-osm-stage FILE      (psql: \copy t FROM PROGRAM 'streetgen-osm-stage "$FILE"')
//
// Why not osm2pgsql, which did this through a flex style: its fixed cost per run (five
// connections, two tables made and analysed in their own sessions, its COPY) was a third of a
// small city's import, and it needs its input sorted (osmium fileinfo, then osmium sort). This
// is the same library osm2pgsql reads with, writing into the import's own session. The geometry
// rules are osm2pgsql's (geom-functions.cpp), so what is staged does not change: a line skips
// nodes without a location (an extract cuts them off) and repeated locations, and is left out
// when fewer than two points remain; areas are assembled with invalid locations ignored.
//
// The input needs no order: a file sorted by type (nodes, ways, relations) is read in one pass,
// any other in two (node locations and relations first, then the ways).
//
// Exit status 0 on success; 1 with a message on stderr when the file cannot be read or parsed
// (psql's \copy FROM PROGRAM then fails, and so does the import).
#include <osmium/area/geom_assembler.hpp>
#include <osmium/geom/wkb.hpp>
#include <osmium/handler/node_locations_for_ways.hpp>
#include <osmium/index/map/flex_mem.hpp>
#include <osmium/io/any_input.hpp>
#include <osmium/osm/area.hpp>
#include <osmium/osm/relation.hpp>
#include <osmium/osm/way.hpp>

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <stdexcept>
#include <string>
#include <tuple>
#include <type_traits>
#include <unordered_map>
#include <unordered_set>
#include <vector>

#if !defined(__BYTE_ORDER__) || __BYTE_ORDER__ != __ORDER_LITTLE_ENDIAN__
#error "streetgen-osm-stage writes little-endian EWKB from the host's own doubles"
#endif

namespace {

using LocationIndex = osmium::index::map::FlexMem<osmium::unsigned_object_id_type, osmium::Location>;
using LocationHandler = osmium::handler::NodeLocationsForWays<LocationIndex, LocationIndex>;

bool is_street_parking(const osmium::TagList& tags) {
    const char* amenity = tags.get_value_by_key("amenity");
    const char* parking = tags.get_value_by_key("parking");
    if (amenity == nullptr || parking == nullptr || std::strcmp(amenity, "parking") != 0) {
        return false;
    }
    return std::strcmp(parking, "street_side") == 0 || std::strcmp(parking, "lane") == 0 ||
           std::strcmp(parking, "layby") == 0;
}

// One COPY text field holding a JSON string: JSON escapes first, then COPY's (a backslash
// doubled, control characters as \t, \n, \r ...).
void append_json_string(std::string& out, const char* s) {
    out += '"';
    for (const char* p = s; *p != '\0'; ++p) {
        const auto c = static_cast<unsigned char>(*p);
        switch (c) {
        case '"': out += "\\\\\""; break;    // JSON \"  -> COPY \\"
        case '\\': out += "\\\\\\\\"; break; // JSON \\  -> COPY \\\\ .
        case '\n': out += "\\\\n"; break;    // JSON \n  -> COPY \\n
        case '\r': out += "\\\\r"; break;
        case '\t': out += "\\\\t"; break;
        default:
            if (c < 0x20) {
                char buf[16];
                std::snprintf(buf, sizeof buf, "\\\\u%04x", c);
                out += buf;
            } else {
                out += static_cast<char>(c);
            }
        }
    }
    out += '"';
}

void append_tags(std::string& out, const osmium::TagList& tags) {
    out += '{';
    bool first = true;
    for (const auto& tag : tags) {
        if (!first) {
            out += ',';
        }
        first = false;
        append_json_string(out, tag.key());
        out += ':';
        append_json_string(out, tag.value());
    }
    out += '}';
}

void append_hex(std::string& out, const void* data, std::size_t size) {
    static const char digits[] = "0123456789ABCDEF";
    const auto* bytes = static_cast<const unsigned char*>(data);
    for (std::size_t i = 0; i < size; ++i) {
        out += digits[bytes[i] >> 4U];
        out += digits[bytes[i] & 0xfU];
    }
}

template <typename T>
void append_hex_value(std::string& out, T value) {
    static_assert(std::is_trivially_copyable<T>::value, "plain values only");
    unsigned char raw[sizeof(T)];
    std::memcpy(raw, &value, sizeof(T));
    append_hex(out, raw, sizeof(T)); // little-endian host, as the EWKB's byte order says
}

// osm2pgsql's line: nodes with a location, repeated locations once; empty when under two points.
bool append_linestring_ewkb(std::string& out, const osmium::WayNodeList& nodes) {
    std::vector<osmium::Location> points;
    points.reserve(nodes.size());
    osmium::Location last{};
    for (const auto& node : nodes) {
        const auto loc = node.location();
        if (loc.valid() && loc != last) {
            points.push_back(loc);
            last = loc;
        }
    }
    if (points.size() <= 1U) {
        return false;
    }
    out += "01";                                    // little endian
    append_hex_value<std::uint32_t>(out, 0x20000002U); // LineString with SRID
    append_hex_value<std::uint32_t>(out, 4326U);
    append_hex_value<std::uint32_t>(out, static_cast<std::uint32_t>(points.size()));
    for (const auto& p : points) {
        append_hex_value<double>(out, p.lon());
        append_hex_value<double>(out, p.lat());
    }
    return true;
}

// The staged rows, written at the end in the order osm2pgsql saw its ways after `osmium sort`
// (libosmium's object order: negative ids first, then by absolute id): the axes' ids follow it.
class Rows {
public:
    void add(const char* kind, osmium::item_type type, osmium::object_id_type id, const osmium::TagList& tags,
             const std::string& geom_hex) {
        const bool relation = type == osmium::item_type::relation;
        std::string line;
        line.reserve(geom_hex.size() + 64 + tags.byte_size());
        line += kind;
        line += relation ? "\tosm:relation/" : "\tosm:way/";
        line += std::to_string(id);
        line += '\t';
        append_tags(line, tags);
        line += '\t';
        line += geom_hex;
        line += '\n';
        rows_.push_back(Row{relation, id > 0, id < 0 ? -id : id, std::move(line)});
    }

    void write_sorted() {
        std::stable_sort(rows_.begin(), rows_.end(), [](const Row& a, const Row& b) {
            return std::tie(a.relation, a.positive, a.magnitude) < std::tie(b.relation, b.positive, b.magnitude);
        });
        for (const auto& row : rows_) {
            if (std::fwrite(row.line.data(), 1, row.line.size(), stdout) != row.line.size()) {
                throw std::runtime_error("cannot write the staged rows (standard output closed?)");
            }
        }
        if (std::fflush(stdout) != 0) {
            throw std::runtime_error("cannot write the staged rows (standard output closed?)");
        }
    }

private:
    struct Row {
        bool relation;
        bool positive;
        osmium::object_id_type magnitude;
        std::string line;
    };
    std::vector<Row> rows_;
};

// Relations of street parking (type=multipolygon), kept whole with the ids of their member ways.
struct ParkingRelations {
    osmium::memory::Buffer relations{1024, osmium::memory::Buffer::auto_grow::yes};
    std::unordered_set<osmium::object_id_type> member_ways;
};

std::string multipolygon_hex(const osmium::Area& area) {
    osmium::geom::WKBFactory<> factory{osmium::geom::wkb_type::ewkb, osmium::geom::out_type::hex};
    return factory.create_multipolygon(area);
}

osmium::area::AssemblerConfig osm2pgsql_area_config() {
    osmium::area::AssemblerConfig config;
    config.ignore_invalid_locations = true;
    return config;
}

// Keeps a street parking relation (type=multipolygon) whole, with the ids of its member ways.
void keep_if_parking_relation(const osmium::Relation& relation, ParkingRelations& parking) {
    const char* type = relation.tags().get_value_by_key("type");
    if (type == nullptr || std::strcmp(type, "multipolygon") != 0 || !is_street_parking(relation.tags())) {
        return;
    }
    parking.relations.add_item(relation);
    parking.relations.commit();
    for (const auto& member : relation.members()) {
        if (member.type() == osmium::item_type::way) {
            parking.member_ways.insert(member.ref());
        }
    }
}

// The ways a street parking relation is made of, kept (with their locations) until it is built.
class MemberWays {
public:
    void keep_if_member(const osmium::Way& way, const ParkingRelations& parking) {
        if (parking.member_ways.count(way.id()) != 0 && offset_.count(way.id()) == 0) {
            offset_.emplace(way.id(), ways_.committed());
            ways_.add_item(way);
            ways_.commit();
        }
    }

    // The street parking relations, from the member ways found (missing ones are left out, as
    // osm2pgsql leaves them out).
    void add_relations(const ParkingRelations& parking, const osmium::area::AssemblerConfig& config, Rows& rows) {
        for (const auto& relation : parking.relations.select<osmium::Relation>()) {
            osmium::memory::Buffer ways{1024, osmium::memory::Buffer::auto_grow::yes};
            for (const auto& member : relation.members()) {
                if (member.type() != osmium::item_type::way) {
                    continue;
                }
                const auto found = offset_.find(member.ref());
                if (found != offset_.end()) {
                    ways.add_item(ways_.get<osmium::Way>(found->second));
                    ways.commit();
                }
            }
            osmium::area::GeomAssembler assembler{config};
            osmium::memory::Buffer area_buffer{1024, osmium::memory::Buffer::auto_grow::yes};
            if (assembler(relation, ways, area_buffer)) {
                rows.add("parking", osmium::item_type::relation, relation.id(), relation.tags(),
                         multipolygon_hex(area_buffer.get<osmium::Area>(0)));
            }
        }
    }

private:
    osmium::memory::Buffer ways_{1024, osmium::memory::Buffer::auto_grow::yes};
    std::unordered_map<osmium::object_id_type, std::size_t> offset_;
};

// A way whose node locations are set: its line if it is a highway, its area if it is street
// parking mapped as a closed way.
void stage_way(const osmium::Way& way, const osmium::area::AssemblerConfig& config, Rows& rows, std::string& geom) {
    if (way.tags().has_key("highway")) {
        geom.clear();
        if (append_linestring_ewkb(geom, way.nodes())) {
            rows.add("way", osmium::item_type::way, way.id(), way.tags(), geom);
        }
    } else if (way.is_closed() && is_street_parking(way.tags()) && way.nodes().size() >= 4U) {
        osmium::area::GeomAssembler assembler{config};
        osmium::memory::Buffer area_buffer{1024, osmium::memory::Buffer::auto_grow::yes};
        if (assembler(way, area_buffer)) {
            rows.add("parking", osmium::item_type::way, way.id(), way.tags(),
                     multipolygon_hex(area_buffer.get<osmium::Area>(0)));
        }
    }
}

// A file sorted by type (every node before every way, every way before every relation: what
// osmium, Geofabrik's extracts, JOSM and Overpass write) is read once: a way's nodes are all
// known when it comes. Returns false, having staged nothing, as soon as an object comes out of
// that order. A street parking relation comes after its member ways, so when there is one, the
// ways are read a second time for its members only (none of ../shared/data/osm's files has one;
// 14 of its 15 are sorted by type, Baltimore's is not). One pass instead of two saves a whole
// decoding, most on XML (expat parses the file again): North Bayreuth's .osm.gz 0.36 → 0.23 s
// of CPU, Krems' 0.13 → 0.08, München's .pbf 0.07 → 0.05 (wall 0.19 → 0.07 under load).
bool stage_in_one_pass(const osmium::io::File& file, const osmium::area::AssemblerConfig& config, Rows& rows) {
    LocationIndex positive;
    LocationIndex negative;
    LocationHandler locations{positive, negative};
    locations.ignore_errors(); // a node the extract lacks: an undefined location, as in osm2pgsql
    ParkingRelations parking;
    Rows staged;
    std::string geom;
    int last_rank = 0; // node 1, way 2, relation 3
    osmium::io::Reader reader{file, osmium::osm_entity_bits::node | osmium::osm_entity_bits::way |
                                        osmium::osm_entity_bits::relation};
    while (osmium::memory::Buffer buffer = reader.read()) {
        for (auto& item : buffer) {
            const int rank = item.type() == osmium::item_type::node  ? 1
                             : item.type() == osmium::item_type::way ? 2
                             : item.type() == osmium::item_type::relation ? 3
                                                                           : 0;
            if (rank == 0) {
                continue;
            }
            if (rank < last_rank) {
                reader.close();
                return false;
            }
            last_rank = rank;
            if (rank == 1) {
                locations.node(static_cast<const osmium::Node&>(item));
            } else if (rank == 2) {
                auto& way = static_cast<osmium::Way&>(item);
                locations.way(way);
                stage_way(way, config, staged, geom);
            } else {
                keep_if_parking_relation(static_cast<const osmium::Relation&>(item), parking);
            }
        }
    }
    reader.close();
    if (!parking.member_ways.empty()) {
        MemberWays members;
        osmium::io::Reader again{file, osmium::osm_entity_bits::way};
        while (osmium::memory::Buffer buffer = again.read()) {
            for (auto& way : buffer.select<osmium::Way>()) {
                if (parking.member_ways.count(way.id()) != 0) {
                    locations.way(way);
                    members.keep_if_member(way, parking);
                }
            }
        }
        again.close();
        members.add_relations(parking, config, staged);
    }
    rows = std::move(staged);
    return true;
}

// Any other order: node locations and the street parking relations in a first pass, the ways
// in a second.
void stage_in_two_passes(const osmium::io::File& file, const osmium::area::AssemblerConfig& config, Rows& rows) {
    LocationIndex positive;
    LocationIndex negative;
    LocationHandler locations{positive, negative}; // (sorts the indexes at the first way if need be)
    locations.ignore_errors();
    ParkingRelations parking;
    {
        osmium::io::Reader reader{file, osmium::osm_entity_bits::node | osmium::osm_entity_bits::relation};
        while (osmium::memory::Buffer buffer = reader.read()) {
            for (const auto& item : buffer) {
                if (item.type() == osmium::item_type::node) {
                    locations.node(static_cast<const osmium::Node&>(item));
                } else if (item.type() == osmium::item_type::relation) {
                    keep_if_parking_relation(static_cast<const osmium::Relation&>(item), parking);
                }
            }
        }
        reader.close();
    }

    MemberWays members;
    std::string geom;
    osmium::io::Reader reader{file, osmium::osm_entity_bits::way};
    while (osmium::memory::Buffer buffer = reader.read()) {
        for (auto& way : buffer.select<osmium::Way>()) {
            locations.way(way);
            stage_way(way, config, rows, geom);
            members.keep_if_member(way, parking);
        }
    }
    reader.close();
    members.add_relations(parking, config, rows);
}

int run(const char* path) {
    const osmium::io::File file{path};
    const auto config = osm2pgsql_area_config();
    Rows rows;
    if (!stage_in_one_pass(file, config, rows)) {
        stage_in_two_passes(file, config, rows);
    }
    rows.write_sorted();
    return 0;
}

} // namespace

int main(int argc, char** argv) {
    if (argc != 2) {
        std::fprintf(stderr, "usage: streetgen-osm-stage FILE (.osm, .osm.gz, .osm.bz2, .pbf)\n");
        return 2;
    }
    try {
        return run(argv[1]);
    } catch (const std::exception& e) {
        std::fprintf(stderr, "streetgen-osm-stage: %s: %s\n", argv[1], e.what());
        return 1;
    }
}
