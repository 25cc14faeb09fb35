#include "statmc/render/checkpoint.h"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <map>
#include <memory>
#include <sstream>
#include <type_traits>
#include <vector>

#include <zlib.h>

#include "statmc/layers/atomic_file.h"
#include "statmc/layers/file_error.h"

namespace statmc::render {

namespace {

constexpr char kMagic[8] = {'S', 'T', 'A', 'T', 'M', 'C', 'C', 'K'};
constexpr int kVersion = 4;  // 2: the guides' squares; 3: no position co-moments;
                             // 4: steering's compact statistics

static_assert(std::is_trivially_copyable_v<StatisticsImage<3>::Pixel> &&
                  std::is_trivially_copyable_v<StatisticsImage<BounceStatistics::kGroup>::Pixel> &&
                  std::is_trivially_copyable_v<SteeringStatistics::Moments>,
              "checkpoints copy the accumulators as bytes");

// Every buffer of the film, in the one order checkpoints store them. `FilmRef` is Film or
// const Film; `visit(vector)` sees each accumulator vector.
template <class FilmRef, class Visit>
void for_each_buffer(FilmRef& film, Visit&& visit)
{
    visit(film.stats.accumulators());
    visit(film.albedo_sum);
    visit(film.normal_sum);
    visit(film.depth_sum);
    visit(film.albedo_squares);
    visit(film.normal_squares);
    if (film.steering) {
        visit(film.steering->counts());
        visit(film.steering->moments());
    }
    if (film.bounces)
        for (auto& group : film.bounces->groups())
            visit(group.accumulators());
}

template <class Vector>
std::size_t bytes_of(const Vector& v)
{
    return v.size() * sizeof(typename Vector::value_type);
}

std::uint32_t crc_of(std::uint32_t crc, const void* data, std::size_t bytes)
{
    return std::uint32_t(crc32_z(crc, static_cast<const Bytef*>(data), bytes));
}

// How the accumulators are laid out in memory: a checkpoint of another build (other
// accumulator types) is refused rather than misread.
std::string memory_layout(const Film& film)
{
    using Stats4 = StatisticsImage<BounceStatistics::kGroup>;
    return "pixel " + std::to_string(sizeof(StatisticsImage<3>::Pixel)) + ", steering " +
           std::to_string(film.steering ? film.steering->layout().quantities() : 0) + " of " +
           std::to_string(sizeof(SteeringStatistics::Moments)) + ", bounce groups " +
           std::to_string(film.bounces ? film.bounces->groups().size() : 0) + " of " +
           std::to_string(sizeof(Stats4::Pixel));
}

// One line per field; a newline inside a value (a strange path) would split it.
std::string one_line(std::string value)
{
    for (char& c : value)
        if (c == '\n' || c == '\r')
            c = '?';
    return value;
}

using Fields = std::map<std::string, std::string>;

Fields identity_fields(const CheckpointIdentity& id)
{
    return {{"scene", one_line(id.scene)},
            {"sceneCrc", std::to_string(id.scene_crc)},
            {"seed", std::to_string(id.seed)},
            {"resolution", std::to_string(id.width) + "x" + std::to_string(id.height)},
            {"task", std::to_string(id.task_index) + "/" + std::to_string(id.task_count)},
            {"samples", std::to_string(id.sample_begin) + ".." + std::to_string(id.sample_end)},
            {"settings", one_line(id.settings)}};
}

std::string header_text(const Fields& fields)
{
    std::string text;
    for (const auto& [key, value] : fields)
        text += key + "=" + value + "\n";
    return text;
}

Fields parse_header(const std::string& text)
{
    Fields fields;
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
        const auto eq = line.find('=');
        if (eq != std::string::npos)
            fields[line.substr(0, eq)] = line.substr(eq + 1);
    }
    return fields;
}

struct FileCloser {
    void operator()(std::FILE* f) const { std::fclose(f); }
};
using File = std::unique_ptr<std::FILE, FileCloser>;

[[noreturn]] void cannot_write(const std::string& path, int error)
{
    throw layers::FileError(path + ": cannot write checkpoint: " + std::strerror(error));
}

void put(std::FILE* f, const void* data, std::size_t bytes, const std::string& path)
{
    if (bytes > 0 && std::fwrite(data, 1, bytes, f) != bytes)
        cannot_write(path, errno ? errno : EIO);
}

}  // namespace

std::string checkpoint_path(const std::string& output) { return output + ".checkpoint"; }

void write_checkpoint(const std::string& path, const Film& film, const CheckpointIdentity& identity,
                      const CheckpointProgress& progress)
{
    std::uint32_t payload_crc = crc_of(0, nullptr, 0);
    std::uint64_t payload_bytes = 0;
    for_each_buffer(film, [&](const auto& v) {
        payload_crc = crc_of(payload_crc, v.data(), bytes_of(v));
        payload_bytes += bytes_of(v);
    });
    Fields fields = identity_fields(identity);
    fields["version"] = std::to_string(kVersion);
    fields["layout"] = memory_layout(film);
    fields["samplesDone"] = std::to_string(progress.samples_done);
    char seconds[32];
    std::snprintf(seconds, sizeof seconds, "%.17g", progress.render_seconds);
    fields["renderSeconds"] = seconds;
    fields["payloadBytes"] = std::to_string(payload_bytes);
    fields["payloadCrc"] = std::to_string(payload_crc);
    const std::string header = header_text(fields);
    const std::uint32_t header_bytes = std::uint32_t(header.size());
    const std::uint32_t header_crc = crc_of(crc_of(0, nullptr, 0), header.data(), header.size());

    layers::write_file_atomically(path, [&](const std::string& temporary) {
        errno = 0;
        File f(std::fopen(temporary.c_str(), "wb"));
        if (!f)
            cannot_write(path, errno);
        put(f.get(), kMagic, sizeof kMagic, path);
        put(f.get(), &header_bytes, sizeof header_bytes, path);
        put(f.get(), header.data(), header.size(), path);
        put(f.get(), &header_crc, sizeof header_crc, path);
        for_each_buffer(film, [&](const auto& v) { put(f.get(), v.data(), bytes_of(v), path); });
        if (std::fflush(f.get()) != 0)
            cannot_write(path, errno ? errno : EIO);
        if (std::fclose(f.release()) != 0)
            cannot_write(path, errno ? errno : EIO);
    });
}

CheckpointProgress read_checkpoint(const std::string& path, Film& film,
                                   const CheckpointIdentity& expected)
{
    auto fail = [&](const std::string& why) -> CheckpointError {
        return CheckpointError("checkpoint " + path + ": " + why);
    };
    File f(std::fopen(path.c_str(), "rb"));
    if (!f)
        throw fail(std::string("cannot open it: ") + std::strerror(errno));
    char magic[sizeof kMagic];
    std::uint32_t header_bytes = 0, header_crc = 0;
    if (std::fread(magic, 1, sizeof magic, f.get()) != sizeof magic ||
        std::memcmp(magic, kMagic, sizeof magic) != 0)
        throw fail("not a statmc-render checkpoint");
    if (std::fread(&header_bytes, sizeof header_bytes, 1, f.get()) != 1 ||
        header_bytes > (1u << 20))
        throw fail("corrupted: the header length is unreadable");
    std::string header(header_bytes, '\0');
    if (std::fread(header.data(), 1, header.size(), f.get()) != header.size() ||
        std::fread(&header_crc, sizeof header_crc, 1, f.get()) != 1)
        throw fail("truncated inside its header");
    if (crc_of(crc_of(0, nullptr, 0), header.data(), header.size()) != header_crc)
        throw fail("corrupted: the header's checksum does not match");
    Fields fields = parse_header(header);
    if (fields["version"] != std::to_string(kVersion))
        throw fail("version " + fields["version"] + ", this statmc-render reads version " +
                   std::to_string(kVersion));

    // The render it belongs to, field by field, so that the message says what differs.
    const Fields want = identity_fields(expected);
    const std::pair<const char*, const char*> checks[] = {
        {"scene", "scene"},
        {"sceneCrc", "scene file's contents (it changed since)"},
        {"seed", "seed"},
        {"resolution", "resolution"},
        {"task", "task"},
        {"samples", "sample range"},
        {"settings", "render settings"}};
    for (const auto& [key, what] : checks)
        if (fields[key] != want.at(key))
            throw fail("belongs to another render (" + std::string(what) + ": '" + fields[key] +
                       "' in the checkpoint, '" + want.at(key) + "' in this render)");
    if (fields["layout"] != memory_layout(film))
        throw fail("written by another build of statmc-render (accumulator layout '" +
                   fields["layout"] + "', this one '" + memory_layout(film) + "')");

    std::uint64_t payload_bytes = 0;
    for_each_buffer(film, [&](const auto& v) { payload_bytes += bytes_of(v); });
    if (fields["payloadBytes"] != std::to_string(payload_bytes))
        throw fail("corrupted: it holds " + fields["payloadBytes"] + " bytes of film, " +
                   std::to_string(payload_bytes) + " expected");
    std::uint32_t crc = crc_of(0, nullptr, 0);
    std::uint64_t read = 0;
    for_each_buffer(film, [&](auto& v) {
        const std::size_t n = std::fread(v.data(), 1, bytes_of(v), f.get());
        read += n;
        crc = crc_of(crc, v.data(), n);
    });
    if (read != payload_bytes)
        throw fail("truncated: " + std::to_string(read) + " of " + std::to_string(payload_bytes) +
                   " bytes of film");
    if (std::fgetc(f.get()) != EOF)
        throw fail("corrupted: bytes after the film");
    if (std::to_string(crc) != fields["payloadCrc"])
        throw fail("corrupted: the film's checksum does not match");
    CheckpointProgress progress;
    try {
        progress.samples_done = std::stoull(fields["samplesDone"]);
        progress.render_seconds = std::stod(fields["renderSeconds"]);
    } catch (const std::exception&) {
        throw fail("corrupted: unreadable samplesDone or renderSeconds");
    }
    if (progress.samples_done > std::uint64_t(expected.sample_end - expected.sample_begin))
        throw fail("corrupted: " + fields["samplesDone"] + " samples done of " +
                   std::to_string(expected.sample_end - expected.sample_begin));
    return progress;
}

}  // namespace statmc::render
