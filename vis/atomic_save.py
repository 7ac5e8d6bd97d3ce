"""Atomic output for the chart scripts: every picture or text file is written to a temporary
name in the same directory (".<name>.tmp.<pid>.<ext>", the extension kept so matplotlib picks
the format), fsync'ed and renamed onto its final name with os.replace, so a killed script leaves
either no file or a complete one, never a half-written PNG."""
import os


def _temporary(path):
    head, name = os.path.split(path)
    stem, ext = os.path.splitext(name)
    return os.path.join(head, f".{stem}.tmp.{os.getpid()}{ext}")


def _commit(tmp, path):
    fd = os.open(tmp, os.O_RDONLY)
    try:
        os.fsync(fd)
    finally:
        os.close(fd)
    os.replace(tmp, path)
    try:
        dfd = os.open(os.path.dirname(path) or ".", os.O_RDONLY | os.O_DIRECTORY)
        try:
            os.fsync(dfd)
        finally:
            os.close(dfd)
    except OSError:
        pass  # file systems that cannot sync directories


def save_figure(fig, path, **kwargs):
    """fig.savefig(path, **kwargs), atomically."""
    tmp = _temporary(path)
    try:
        fig.savefig(tmp, **kwargs)
        _commit(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
    finally:
        _release(fig)


def _release(fig):
    """Frees a saved matplotlib figure (many pictures are drawn in one process: vis/batch.py)."""
    try:
        import matplotlib.pyplot as plt
        plt.close(fig)
    except Exception:  # not a pyplot figure
        pass


def write_text(path, text):
    """open(path, "w").write(text), atomically."""
    tmp = _temporary(path)
    try:
        with open(tmp, "w") as f:
            f.write(text)
        _commit(tmp, path)
    except BaseException:
        if os.path.exists(tmp):
            os.remove(tmp)
        raise
