"""solve_batch over chunks on a dask.distributed LocalCluster (Debian python3-distributed): the
path to a cluster, with nothing home-made. Worker processes import pdd through PYTHONPATH; the
chunks go out and the result arrays come back pickled; the concatenation is bit for bit one
solve_batch over all pairs. Small: 4000 pairs in 8 chunks, 2 workers of one thread."""
import numpy as np
import pytest

import pdd

distributed = pytest.importorskip("distributed", reason="dask.distributed is not importable (Debian python3-distributed)")


def solve_chunk(chunk):
    A, B = chunk
    return pdd.solve_batch(A, B, threads=1)


@pytest.mark.parametrize("processes", [False, True])
def test_solve_batch_over_chunks_on_a_local_cluster(processes):
    A, B = np.random.default_rng(17).uniform(0, 10, (2, 4000, 4, 3))
    B[123] = [[0, 0, 0], [1, 0, 0], [0, 1, 0], [1, 1, 0]]  # a rejected pair travels as an entry
    chunks = [(A[k:k + 500], B[k:k + 500]) for k in range(0, len(A), 500)]
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=processes,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        parts = client.gather(client.map(solve_chunk, chunks))
    whole = pdd.solve_batch(A, B)
    for k in ("pdd2", "rigid_pd2", "pdd2_accel6", "q1_A"):
        joined = np.concatenate([p[k] for p in parts])
        assert (joined.view(np.int64) == whole[k].view(np.int64)).all(), k
    assert (np.concatenate([p["pdd2_dir"] for p in parts]) == whole["pdd2_dir"]).all()
    assert sum((p["error"] for p in parts), []) == whole["error"]
    assert whole["error"][123].startswith("tetrahedron B is flat")
