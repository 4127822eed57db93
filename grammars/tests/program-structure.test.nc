( SYNTAX TEST "source.fanuc-macro" "tape marks, program numbers, sequence numbers, block delete, comments"
%
(<- keyword.other.tape-mark.fanuc-macro
O3331 (EXTERNAL THREAD)
(<- storage.type.program.fanuc-macro
(^^^^ entity.name.function.program.fanuc-macro
(     ^ comment.block.fanuc-macro punctuation.definition.comment.begin.fanuc-macro
(      ^^^^^^^^^^^^^^^ comment.block.fanuc-macro
(                     ^ comment.block.fanuc-macro punctuation.definition.comment.end.fanuc-macro
o0013
(<- storage.type.program.fanuc-macro
(^^^^ entity.name.function.program.fanuc-macro
:1234
(<- storage.type.program.fanuc-macro
(^^^^ entity.name.function.program.fanuc-macro
O1234<THREAD_M50>
(<- storage.type.program.fanuc-macro
(^^^^ entity.name.function.program.fanuc-macro
(    ^ punctuation.definition.program-name.begin.fanuc-macro
(     ^^^^^^^^^^ entity.name.function.program.fanuc-macro
(               ^ punctuation.definition.program-name.end.fanuc-macro
O<MAIN>
(<- storage.type.program.fanuc-macro
( ^^^^ entity.name.function.program.fanuc-macro
N10 G0 X100.
(<--- entity.name.tag.sequence-number.fanuc-macro
n20g1
(<--- entity.name.tag.sequence-number.fanuc-macro
(  ^^ keyword.other.gcode.fanuc-macro
N 30 M3
(<---- entity.name.tag.sequence-number.fanuc-macro
/N40 M1
(<- keyword.control.block-delete.fanuc-macro
(^^^ entity.name.tag.sequence-number.fanuc-macro
/1 G0 Z5.
(<-- keyword.control.block-delete.fanuc-macro
/9N50
(<-- keyword.control.block-delete.fanuc-macro
( ^^^ entity.name.tag.sequence-number.fanuc-macro
  /2 M0
( ^^ keyword.control.block-delete.fanuc-macro
#1=#2/2
(    ^ keyword.operator.arithmetic.fanuc-macro - keyword.control.block-delete.fanuc-macro
(外螺纹 M50X3 螺距 3)
(<- comment.block.fanuc-macro punctuation.definition.comment.begin.fanuc-macro
(^^^^^^^^^^^^^^ comment.block.fanuc-macro - support.type.mcode.fanuc-macro entity.other.attribute-name.address.fanuc-macro
(              ^ comment.block.fanuc-macro punctuation.definition.comment.end.fanuc-macro
G0 (IF GOTO #1 (NOT NESTED) X1.
(   ^^^^^^^^^^^^^^^^^^^^^^ comment.block.fanuc-macro - keyword.control.conditional.fanuc-macro keyword.control.goto.fanuc-macro variable.parameter.local.fanuc-macro
(                           ^ entity.other.attribute-name.address.fanuc-macro - comment.block.fanuc-macro
(                            ^^ constant.numeric.fanuc-macro - comment.block.fanuc-macro
G1 X1. (UNTERMINATED COMMENT
(       ^^^^^^^^^^^^^^^^^^^^ comment.block.fanuc-macro
#3000=1(ALARM 1 门未关)
(       ^^^^^^^^^^^ comment.block.fanuc-macro
G0X0;
(   ^ punctuation.terminator.end-of-block.fanuc-macro
(TOOL (T0101) BORING BAR)
(^^^^^^^^^^^ comment.block.fanuc-macro
(           ^ comment.block.fanuc-macro punctuation.definition.comment.end.fanuc-macro
(                       ^ invalid.illegal.unmatched-parenthesis.fanuc-macro - comment.block.fanuc-macro
%
(<- keyword.other.tape-mark.fanuc-macro
