"""What every tool in tools/ shares: one set of exit codes and messages, and the figure options.

    ap = rondel.cli.ArgumentParser("shear", description=...)   # usage errors exit 1, not argparse's 2
    rondel.cli.add_figure_options(ap)                        # --format png|pdf|svg, --dpi
    sys.exit(rondel.cli.run_tool("shear", main_body, args))  # RondelError -> one line on stderr

Exit codes (rondel.errors): 0 done; 1 bad input or usage ('TOOL: error: MESSAGE' on stderr, no
traceback); 2 a run or a check failed."""
import argparse
import os
import sys

from .errors import EXIT_INPUT, EXIT_OK, RondelError

FORMATS = ("png", "pdf", "svg")
EXIT_HELP = ("exit status: 0 done; 1 bad input or usage (one line 'TOOL: error: ...' on stderr); "
             "2 a run or a check failed. See docs/python.md.")


class ArgumentParser(argparse.ArgumentParser):
    """argparse with the tools' conventions: a usage error is 'TOOL: error: MESSAGE' and exit status 1."""

    def __init__(self, tool, **kw):
        epilog = kw.pop("epilog", None)
        kw.setdefault("formatter_class", argparse.RawDescriptionHelpFormatter)
        super().__init__(prog=kw.pop("prog", tool), epilog=(epilog + "\n\n" if epilog else "")
                         + EXIT_HELP.replace("TOOL", tool), **kw)
        self.tool = tool

    def error(self, message):
        self.print_usage(sys.stderr)
        print(f"{self.tool}: error: {message}", file=sys.stderr)
        sys.exit(EXIT_INPUT)


def fail(tool, message, code=EXIT_INPUT):
    """Print 'TOOL: error: MESSAGE' on stderr and return CODE (for `return fail(...)` in main)."""
    print(f"{tool}: error: {message}", file=sys.stderr)
    return code


def run_tool(tool, body, *args):
    """Call BODY(*ARGS) and turn the errors a user can cause into one line and an exit code."""
    try:
        rc = body(*args)
        return EXIT_OK if rc is None else rc
    except RondelError as e:
        return fail(tool, str(e), e.code)
    except ImportError as e:
        return fail(tool, f"the Python module {e.name} is missing for {sys.executable}: run the tool with "
                    "Debian's /usr/bin/python3 (apt-get install python3-numpy python3-h5py python3-matplotlib)")
    except BrokenPipeError:  # the reader of our output went away (| head): not an error of the tool
        sys.stderr.close()
        return EXIT_OK
    except KeyboardInterrupt:
        return fail(tool, "interrupted", 130)


def add_figure_options(ap, dpi=150, no_plot=True):
    """--format png|pdf|svg (default png), --dpi (raster resolution; PDF and SVG keep vectors) and, with
    NO_PLOT, --no-plot (CSV files only)."""
    g = ap.add_argument_group("figures")
    g.add_argument("--format", choices=FORMATS, default="png", help="figure file format (default png)")
    g.add_argument("--dpi", type=float, default=dpi,
                   help=f"resolution of raster figures and of images inside PDF/SVG (default {dpi:g})")
    if no_plot:
        g.add_argument("--no-plot", action="store_true", help="write the CSV files only, no figures")
    return g


def check_figure_options(ap, args):
    if args.dpi <= 0 or args.dpi > 2400:
        ap.error(f"--dpi {args.dpi:g} is out of range (0, 2400]")


def pyplot():
    """matplotlib.pyplot on the file-only Agg back end, with fonts embedded as text in PDF and SVG."""
    import matplotlib
    matplotlib.use("Agg")
    matplotlib.rcParams["pdf.fonttype"] = 42  # TrueType: editable text in PDF, accepted by journals
    matplotlib.rcParams["svg.fonttype"] = "none"
    import matplotlib.pyplot as plt
    return plt


def save_figure(fig, stem, args, tight=True):
    """Write FIG to STEM.<args.format> at args.dpi and close it; returns the path.

    tight: crop to the drawn content (bbox_inches='tight'), so that no label or colour-bar text is clipped;
    a figure with constrained layout and a width that must be kept exactly passes tight=False."""
    path = f"{stem}.{args.format}"
    os.makedirs(os.path.dirname(os.path.abspath(path)), exist_ok=True)
    kw = {"bbox_inches": "tight", "pad_inches": 0.05} if tight else {}
    if args.format == "pdf":
        kw["metadata"] = {"Creator": "Rondel tools", "CreationDate": None}  # reproducible bytes
    elif args.format == "svg":
        kw["metadata"] = {"Date": None}
    fig.savefig(path, dpi=args.dpi, format=args.format, **kw)
    import matplotlib.pyplot as plt
    plt.close(fig)
    return path
