// `candela`: renders a scene dump (docs/architecture.md) to an OpenEXR file without Blender, with the
// same image as the add-on for the same seed. For debugging, benchmarks and render farms.
//   candela DUMP_DIR -o out.exr [--samples N] [--seed N] [--threads N] [--set key=value ...]
#include <CLI/CLI.hpp>

#include <csignal>
#include <cstdio>
#include <iostream>

#include "cli/scene_dump.h"
#include "core/error.h"
#include "film/exr_io.h"
#include "session/session.h"

namespace {

volatile std::sig_atomic_t g_interrupted = 0;
void on_sigint(int) { g_interrupted = 1; }

candela::Params::Value parse_value(const std::string& s) {
    if (s == "true" || s == "false") return s == "true";
    try {
        size_t used = 0;
        const long long i = std::stoll(s, &used);
        if (used == s.size()) return static_cast<int64_t>(i);
        const double d = std::stod(s, &used);
        if (used == s.size()) return d;
    } catch (const std::exception&) {}
    return s;
}

}  // namespace

int main(int argc, char** argv) {
    CLI::App app{"Candela: render a scene dump to OpenEXR"};
    std::string dump_dir, output = "candela.exr";
    int samples = -1, threads = -1;
    int64_t seed = -1;
    std::vector<std::string> overrides;
    bool quiet = false;
    app.add_option("dump", dump_dir, "scene dump directory (params.json + *.npy)")->required();
    app.add_option("-o,--output", output, "output EXR path");
    app.add_option("--samples", samples, "samples per pixel (overrides the dump)");
    app.add_option("--seed", seed, "random seed (overrides the dump)");
    app.add_option("--threads", threads, "render threads, 0 = all (overrides the dump)");
    app.add_option("--set", overrides, "override a parameter: key=value");
    app.add_flag("-q,--quiet", quiet, "print only errors");
    CLI11_PARSE(app, argc, argv);

    try {
        candela::SceneDump dump = candela::read_scene_dump(dump_dir);
        if (samples > 0) dump.params.set("samples", int64_t(samples));
        if (seed >= 0) dump.params.set("seed", seed);
        if (threads >= 0) dump.params.set("threads", int64_t(threads));
        for (const auto& kv : overrides) {
            const size_t eq = kv.find('=');
            if (eq == std::string::npos) throw candela::InvalidParameter("--set expects key=value, got '" + kv + "'");
            dump.params.set(kv.substr(0, eq), parse_value(kv.substr(eq + 1)));
        }
        for (const auto& w : dump.warnings) std::cerr << "warning: " << w << "\n";

        candela::Session session(std::move(dump.arrays), std::move(dump.params));
        std::signal(SIGINT, on_sigint);
        session.start();
        int64_t last_reported = -1;
        while (!session.wait(0.1)) {
            if (g_interrupted) session.cancel();
            const auto p = session.progress();
            if (!quiet && p.work_done != last_reported) {
                std::fprintf(stderr, "\r%s: %s %lld/%lld", candela::phase_name(p.phase), p.unit.c_str(),
                             (long long)p.work_done, (long long)p.work_total);
                last_reported = p.work_done;
            }
        }
        session.join();
        if (!quiet) std::fprintf(stderr, "\n");
        for (const auto& e : session.take_log_entries()) {
            if (e.level == candela::LogLevel::Info && quiet) continue;
            std::cerr << (e.level == candela::LogLevel::Info ? "info: " : "warning: ") << e.message << "\n";
        }
        if (auto err = session.error()) {
            std::cerr << "error: " << *err << "\n";
            return 1;
        }
        int channels = 0;
        const std::vector<float> rgba = session.get_pass("Combined", &channels);
        candela::write_exr_rgba(output, session.width(), session.height(), rgba);
        const auto st = session.stats();
        if (!quiet)
            std::printf(
                "Candela: %dx%d, %d samples/pixel in %.3f s render (%.3f s build): %.0f samples/s, %.0f rays/s -> "
                "%s%s\n",
                session.width(), session.height(), int(session.progress().work_done), st.render_seconds,
                st.build_seconds, st.samples_per_second,
                st.render_seconds > 0 ? double(st.rays) / st.render_seconds : 0.0, output.c_str(),
                g_interrupted ? " (cancelled: partial image)" : "");
        return g_interrupted ? 130 : 0;
    } catch (const std::exception& e) {
        std::cerr << "error: " << e.what() << "\n";
        return 1;
    }
}
