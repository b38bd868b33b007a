"""The work-precision study's table and figure (rockcut accuracy, docs/record/accuracy.md)."""

SHORT = {"force_horizontal_mean_n_per_m": "Fh", "force_horizontal_peak_n_per_m": "Fh peak",
         "force_vertical_mean_n_per_m": "Fv",
         "breaks": "breaks", "pressure_p1_mean_pa": "P1", "pressure_p2_mean_pa": "P2",
         "pressure_p3_mean_pa": "P3"}


def markdown(table, seeds, keys):
    """The study's table: each setting's error and seed scatter of every key, in markdown."""
    head = "| ladder | setting | N | particles | wall [s] | " + " | ".join(
        "%s err (scatter)" % SHORT[k] for k in keys) + " |"
    lines = [head, "|" + "---|" * (5 + len(keys))]
    for e in table:
        if e.get("missing"):
            lines.append("| %s | %s | | | | %s |" % (e["ladder"], e["setting"], " | ".join("-" for _ in keys)))
            continue
        cells = ["%.0f %% (%.0f %%)" % (100 * e["error_" + k], 100 * e["scatter_" + k]) for k in keys]
        lines.append("| %s | %s | %s | %s | %.1f | %s |" % (
            e["ladder"], e["setting"], e["coupling_interval"], e["particles"], e["wall_time_s"],
            " | ".join(cells)))
    return ("Errors against the finest setting of each ladder (mean over seeds %s); in brackets the\n"
            "standard error of the mean over the seeds, relative to the finest value.\n\n"
            % ",".join(map(str, seeds))) + "\n".join(lines) + "\n"


def plot(table, path, ladder_names, force):
    """Error of the `force` ("mean" or "peak") horizontal force against wall time, per ladder."""
    from .figures import plt
    key = "force_horizontal_%s_n_per_m" % force
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for ladder in ladder_names:
        es = [e for e in table if e["ladder"] == ladder and not e.get("missing")][:-1]  # not the reference
        if not es:
            continue
        x = [e["wall_time_s"] for e in es]
        y = [max(e["error_" + key], 1e-4) for e in es]
        ax.loglog(x, y, "o-", label=ladder)
        for e, xi, yi in zip(es, x, y):
            ax.annotate(e["setting"], (xi, yi), textcoords="offset points", xytext=(4, 4), fontsize=8)
        sc = [e["scatter_" + key] for e in es]
        ax.loglog(x, sc, ":", color=ax.lines[-1].get_color(), alpha=0.6)
    ax.axhline(0.05, color="grey", lw=0.8, ls="--")
    ax.set_xlabel("wall time per run [s]")
    ax.set_ylabel("relative error of the %s horizontal force" % force)
    ax.set_title("Work-precision, reduced saturated cut (dotted: seed scatter)")
    ax.legend()
    fig.tight_layout()
    fig.savefig(path, dpi=120)
