( SYNTAX TEST "source.fanuc-macro" "IF, GOTO, THEN, WHILE, DO, END without spaces and in any case"
IF[#1EQ#102]GOTO2010
(<-- keyword.control.conditional.fanuc-macro
( ^ punctuation.section.brackets.begin.fanuc-macro
(  ^^ variable.parameter.local.fanuc-macro
(    ^^ keyword.operator.comparison.fanuc-macro
(      ^^^^ variable.other.common.fanuc-macro
(          ^ punctuation.section.brackets.end.fanuc-macro
(           ^^^^ keyword.control.goto.fanuc-macro
(               ^^^^ constant.numeric.label.fanuc-macro
N45IF[#100GE#18]GOTO2
(<--- entity.name.tag.sequence-number.fanuc-macro
(  ^^ keyword.control.conditional.fanuc-macro
(     ^^^^ variable.other.common.fanuc-macro
(         ^^ keyword.operator.comparison.fanuc-macro
(           ^^^ variable.parameter.local.fanuc-macro
(               ^^^^ keyword.control.goto.fanuc-macro
(                   ^ constant.numeric.label.fanuc-macro
IF [#1 NE #0] GOTO 20
(<-- keyword.control.conditional.fanuc-macro
(      ^^ keyword.operator.comparison.fanuc-macro
(         ^^ variable.language.null.fanuc-macro
(             ^^^^ keyword.control.goto.fanuc-macro
(                  ^^ constant.numeric.label.fanuc-macro
if[#1lt0.5]goto#10
(<-- keyword.control.conditional.fanuc-macro
(    ^^ keyword.operator.comparison.fanuc-macro
(      ^^^ constant.numeric.fanuc-macro
(          ^^^^ keyword.control.goto.fanuc-macro
(              ^^^ variable.parameter.local.fanuc-macro
GOTO[#1+10]
(<---- keyword.control.goto.fanuc-macro
(   ^ punctuation.section.brackets.begin.fanuc-macro
IF[#1GT#2]THEN#3=#1
(<-- keyword.control.conditional.fanuc-macro
(    ^^ keyword.operator.comparison.fanuc-macro
(         ^^^^ keyword.control.conditional.fanuc-macro
(             ^^ variable.parameter.local.fanuc-macro
IF[#1LE0]THEN
(    ^^ keyword.operator.comparison.fanuc-macro
(        ^^^^ keyword.control.conditional.fanuc-macro
ELSE
(<---- keyword.control.conditional.fanuc-macro
ENDIF
(<----- keyword.control.conditional.fanuc-macro - keyword.control.loop.fanuc-macro
WHILE[#107LT[#104+1]]DO1
(<----- keyword.control.loop.fanuc-macro
(    ^ punctuation.section.brackets.begin.fanuc-macro
(     ^^^^ variable.other.common.fanuc-macro
(         ^^ keyword.operator.comparison.fanuc-macro
(           ^ punctuation.section.brackets.begin.fanuc-macro
(            ^^^^ variable.other.common.fanuc-macro
(                ^ keyword.operator.arithmetic.fanuc-macro
(                 ^ constant.numeric.fanuc-macro
(                  ^^ punctuation.section.brackets.end.fanuc-macro
(                    ^^ keyword.control.loop.fanuc-macro
(                      ^ constant.numeric.loop-id.fanuc-macro
WH[#1LT10]DO2
(<-- keyword.control.loop.fanuc-macro
(         ^^ keyword.control.loop.fanuc-macro
(           ^ constant.numeric.loop-id.fanuc-macro
while [#2 ge 0] do 3
(<----- keyword.control.loop.fanuc-macro
(         ^^ keyword.operator.comparison.fanuc-macro
(               ^^ keyword.control.loop.fanuc-macro
(                  ^ constant.numeric.loop-id.fanuc-macro
#1=#1+1
(    ^ keyword.operator.arithmetic.fanuc-macro
END1
(<--- keyword.control.loop.fanuc-macro
(  ^ constant.numeric.loop-id.fanuc-macro
N100END2
(<---- entity.name.tag.sequence-number.fanuc-macro
(   ^^^ keyword.control.loop.fanuc-macro
(      ^ constant.numeric.loop-id.fanuc-macro
end 3
(<--- keyword.control.loop.fanuc-macro
(   ^ constant.numeric.loop-id.fanuc-macro
N2010 M99
(<----- entity.name.tag.sequence-number.fanuc-macro
(     ^^^ keyword.control.call.fanuc-macro
