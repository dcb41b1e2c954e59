//! HDF5 write through the library's run writer (`cargo bench --bench store`; throughput in bytes/s):
//! `RunWriter::create` → one `write_shard` per 50 realizations → `finish` (close, fsync, rename), the path
//! `simulate` takes to store raw realizations, for 64 × 2¹⁶ f64 (33.5 MB) uncompressed and 16 × 2¹⁶ f64
//! with shuffle + deflate level 1, into a temporary directory. The 524 MB job against h5py is in
//! `examples/compare_rust.rs` (`benches/compare/run.sh`).

#[path = "h5chain/mod.rs"]
mod h5chain;

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use h5chain::{h5_data, h5_tmpdir, h5_write_library, H5_COLS};
use std::time::{Duration, Instant};
use stochvib::store::{tmp_path, Compression};

fn store_bench(c: &mut Criterion) {
    let dir = h5_tmpdir("criterion");
    let mut g = c.benchmark_group("hdf5_write");
    g.sample_size(10);
    g.warm_up_time(Duration::from_millis(500));
    g.measurement_time(Duration::from_secs(3));
    for (name, rows, comp) in [
        ("none_64x2^16", 64, Compression::None),
        ("deflate1_16x2^16", 16, Compression::DEFLATE_FAST),
    ] {
        let data = h5_data(rows, H5_COLS);
        let path = dir.join(format!("{name}.h5"));
        g.throughput(Throughput::Bytes((rows * H5_COLS * 8) as u64));
        g.bench_function(name, |b| {
            b.iter_custom(|iters| {
                let mut total = Duration::ZERO;
                for _ in 0..iters {
                    let _ = std::fs::remove_file(&path);
                    let _ = std::fs::remove_file(tmp_path(&path));
                    let t0 = Instant::now();
                    let done = h5_write_library(&path, &data, comp, true);
                    total += t0.elapsed();
                    std::fs::remove_file(done).unwrap();
                }
                total
            })
        });
    }
    g.finish();
    let _ = std::fs::remove_dir_all(&dir);
}

criterion_group!(benches, store_bench);
criterion_main!(benches);
