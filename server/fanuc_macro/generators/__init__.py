"""Program generators: the symmetric thread module (seed 000), the arc thread (seed 002) and the
drum groove (seed 003), and the editor's requests for them. Each writes Macro B text and checks
it by running it with the evaluator. The modules load when first used: a start of the language
server or a check loads none of them."""
