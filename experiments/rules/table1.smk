# Table 1 (make reproduce-table): the paper's grid, analysed by rules/grid.smk.
include: "grid.smk"

# the report
localrules: table1

rule table1:
    input:
        F["table"] + ".md",
        F["equal_error"] + ".md",
