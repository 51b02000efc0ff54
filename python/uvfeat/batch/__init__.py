"""Many meshes, and long animations, on a Dask cluster: ``uvfeat.batch(paths, features, radius,
client=None, **options)`` and ``uvfeat batch``; ``uvfeat animate --scheduler`` runs its frames
in chunks on the same machinery. Dask and pyarrow are imported only when a run starts
(``pip install 'uvfeat[batch]'``)."""

from .run import batch

__all__ = ["batch"]
