# Sphinx configuration of Swell's documentation (docs/). Built by scripts/docs:
#   sphinx-build -W --keep-going -b html docs build/docs-html
# with Debian 12's python3-sphinx (5.3), python3-myst-parser (0.18) and furo (2022.12).
# Every page is Markdown (MyST). Warnings are errors in scripts/docs and CI; nothing is
# suppressed here.

project = "Swell"
author = "the Swell developers"
copyright = "the Swell developers"

extensions = ["myst_parser"]
source_suffix = {".md": "markdown"}
root_doc = "index"

# `[text](page.md#a-heading)` links: MyST gives headings of levels 1-4 an anchor (GitHub's
# slug rule), so the same links work on GitHub and in the HTML, and a link to a heading that
# does not exist is a warning (an error under -W). Level 4: the generated
# case_reference.md and several pages link to ####-level sections.
myst_heading_anchors = 4
myst_enable_extensions = ["dollarmath", "deflist"]

# Not pages: the mapping of moved README sections for the code's comments.
exclude_patterns = ["_readme_moves.txt", "_build"]

html_theme = "furo"
html_title = "Swell"

# The link check (`-b linkcheck`, run by scripts/docs) checks every internal link and anchor;
# links to the web are not checked (CI has no internet).
linkcheck_ignore = [r"https?://.*"]
linkcheck_anchors = True
