// Cbtl.g4 — the grammar of the .cbtl language.
//
// The grammar only describes shape. Everything that needs names or types (is `reel` a type? does a
// generator's arity match its parameters? is a feature real-valued?) is checked by the compiler's
// semantic passes, where the messages can be precise. Built-in types (real, int, vec<3>, Conf<gen3>,
// ...) are therefore plain identifiers here, and model / sampler / function names are ordinary calls.
//
// The reference for users is docs/language.md; keep both in step.
grammar Cbtl;

// ---------------------------------------------------------------------------------------------
// Files and top-level declarations
// ---------------------------------------------------------------------------------------------

// file := domain-header? declaration* EOF
file        : domainDecl? topDecl* EOF ;

domainDecl  : DOMAIN qualifiedName SEMI ;
qualifiedName : ident (DOT ident)* ;

// A domain header after the first declaration is accepted here so that the compiler can say what is
// wrong with it (E0211) instead of reporting a syntax error.
topDecl
    : domainDecl
    | importDecl
    | worldDecl
    | simulatorDecl
    | robotDecl
    | clearanceDecl
    | constDecl
    | enumDecl
    | itemDecl
    | itemsDecl
    | observeDecl
    | feedbackDecl
    | funcDecl
    | samplerDecl
    | actionDecl
    | personalDecl
    | skillDecl
    | taskDecl
    | scopeStmt
    ;

// import std.geometry;   import "shared/common.cbtl";
importDecl  : IMPORT (qualifiedName | STRING) SEMI ;

// world "feeding.xml";
worldDecl   : WORLD STRING SEMI ;

// simulator "python3 coffee_sim.py";   (an external simulator: docs/simulator-protocol.md)
simulatorDecl : SIMULATOR STRING SEMI ;

// robot gen3 { dof: 7; }
robotDecl   : ROBOT ident LBRACE (fieldInit SEMI)* RBRACE ;

// clearance person: "user", "user_head" >= 5 cm;   (scene bodies the robot keeps this far from)
clearanceDecl : CLEARANCE ident COLON STRING (COMMA STRING)* GE lengthLit SEMI ;

// 5 cm   0.05 m   12.5 mm. The unit is a name, checked by the compiler (m, cm, mm), so that `m` stays usable as a
// name everywhere else; a minus sign is accepted here only so that a negative length gets a precise message.
lengthLit   : MINUS? NUMBER ident? ;

// const heatRate = 0.1;   const radius[Pot] : real = [0.5, 1.0, 0.5, 0.5];
constDecl   : CONST ident indexSpec? (COLON typeRef)? ASSIGN expr SEMI ;

// [Ingredient]  [i in Ingredient]  [0 .. 3]
indexSpec   : LBRACK (ident IN)? expr RBRACK ;

// enum Dip { ketchup, bbq, ranch, none }
enumDecl    : ENUM ident LBRACE ident (COMMA ident)* COMMA? RBRACE ;

// item Book { title: text; author: text; tags: set<text>; }
itemDecl    : ITEM ident LBRACE fieldDecl* RBRACE ;
fieldDecl   : ident COLON typeRef SEMI ;

// items standardBooks : Book { cosmos { title: "Cosmos", ... }, ... }
itemsDecl   : ITEMS ident COLON typeRef LBRACE itemEntry (COMMA itemEntry)* COMMA? RBRACE ;
itemEntry   : ident LBRACE (fieldInit (COMMA fieldInit)* COMMA?)? RBRACE ;
fieldInit   : ident COLON expr ;

// observe stock[Ingredient] : real;
observeDecl : OBSERVE ident indexSpec? COLON typeRef SEMI ;

// feedback critique(ing: Ingredient, temp: real, good: bool);
feedbackDecl : FEEDBACK ident LPAREN paramList? RPAREN SEMI ;

// extern fn distance<N>(a: vec<N>, b: vec<N>) -> real;     fn cooked(t: int) -> real = t * 0.1;
funcDecl    : EXTERN? FN ident typeParams? LPAREN paramList? RPAREN ARROW typeRef (ASSIGN expr)? SEMI ;

// extern sampler ikAbove<R>(pose: SE2, height: real) -> Conf<R>;
samplerDecl : EXTERN SAMPLER ident typeParams? LPAREN paramList? RPAREN ARROW typeRef SEMI ;

// extern action moveArm<R>(q: Conf<R>);
actionDecl  : EXTERN ACTION ident typeParams? LPAREN paramList? RPAREN SEMI ;

typeParams  : LT ident (COMMA ident)* GT ;
paramList   : param (COMMA param)* ;
param       : ident COLON typeRef ;

// real   vec<3>   Conf<gen3>   set<Book>   Dip
typeRef     : ident (LT typeArg (COMMA typeArg)* GT)? ;
typeArg     : NUMBER | typeRef ;

// ---------------------------------------------------------------------------------------------
// Statements allowed at top level, in skills and in tasks
// ---------------------------------------------------------------------------------------------

scopeStmt
    : varDecl
    | requireDecl
    | sampleDecl
    | costDecl
    ;

// var temp[Ingredient] : real in 2.5 .. 3.5 = 3.0;
varDecl     : VAR ident indexSpec? COLON typeRef (IN expr)? (ASSIGN expr)? SEMI ;

// require distinctPots: forall a, b in Ingredient where a != b: pot[a] != pot[b];
requireDecl : REQUIRE (ident COLON)? expr SEMI ;

// sample temp[i] ~ uniform for i in Ingredient;    sample q ~ ikAbove(plate, 0.08);
sampleDecl  : SAMPLE expr (COMMA expr)* TILDE ident (LPAREN argList? RPAREN)? (FOR binder)? SEMI ;

// minimize distance(a, b);
costDecl    : (MINIMIZE | MAXIMIZE) expr SEMI ;

// ---------------------------------------------------------------------------------------------
// Personalized constraint generators
// ---------------------------------------------------------------------------------------------

// personal occlusionFree(c: Conf<gen3>) { when c ~ "*Conf"; model threshold(...); learn ...; }
personalDecl : PERSONAL ident LPAREN paramList? RPAREN LBRACE personalClause* RBRACE ;

personalClause
    : WHEN patternClause (COMMA patternClause)* SEMI                            # whenClause
    | MODEL modelFactor (STAR modelFactor)* (PER expr (COMMA expr)*)? SEMI      # modelClause
    | ACCEPT expr SEMI                                                          # acceptClause
    | FALLBACK expr SEMI                                                        # fallbackClause
    | EXPLORE ident SEMI                                                        # exploreClause
    | IF expr SEMI                                                              # guardClause
    | LEARN ident LPAREN (learnBinder (COMMA learnBinder)*)? RPAREN
            ARROW_FAT labelItem (COMMA labelItem)* (IF expr)? SEMI              # learnClause
    ;

// c ~ "*Conf"    c ~ regex ".*Conf$"    t ~ glob "*temp[{ing}]"
patternClause : ident TILDE (GLOB | REGEX)? STRING ;

// interval(t, 2.5 .. 3.5)     temp = interval(t, 2.5 .. 3.5)
modelFactor : (ident ASSIGN)? ident LPAREN argList? RPAREN ;

learnBinder : ident | UNDERSCORE ;

// false     temp: tGood
labelItem   : (ident COLON)? expr ;

// ---------------------------------------------------------------------------------------------
// Skills and tasks
// ---------------------------------------------------------------------------------------------

// skill bringPlate(plate: SE2) { var ...; require ...; sample ...; do { movePlate(plate); } }
skillDecl   : SKILL ident (LPAREN paramList? RPAREN)? LBRACE skillItem* RBRACE ;
skillItem   : scopeStmt | doStmt ;

doStmt      : DO actionStmt ;

actionStmt
    : ident LPAREN argList? RPAREN SEMI                                            # actionCall
    | FOR binder LBRACE actionStmt* RBRACE                                         # actionFor
    | IF expr LBRACE actionStmt* RBRACE (ELSE LBRACE actionStmt* RBRACE)?          # actionIf
    | LBRACE actionStmt* RBRACE                                                    # actionBlock
    | ALLOW allowPart modeWord=ident targetExpr=expr lengthLit LBRACE actionStmt* RBRACE # actionAllow
    ;

// allow held near person 5 mm { ... }: the part (robot | gripper | held) and the mode (near | touch) are names
// checked by the compiler, so that they stay usable as names elsewhere; `robot` is a keyword, accepted here.
allowPart   : ROBOT | ident ;

// task feedBite = bringPlate then pickUtensil then transferBite;
// task feedBite { var plate : SE2; run bringPlate(plate) then transferBite(plate); }
taskDecl
    : TASK ident ASSIGN skillInstance (THEN skillInstance)* SEMI                   # taskShort
    | TASK ident LBRACE taskItem* RBRACE                                           # taskBlock
    ;
taskItem    : scopeStmt | RUN skillInstance (THEN skillInstance)* SEMI ;
skillInstance : ident (LPAREN argList? RPAREN)? (AS ident)? ;

// ---------------------------------------------------------------------------------------------
// Expressions, loosest binding first in the list below is last in the rule (ANTLR: first = tightest)
// ---------------------------------------------------------------------------------------------

binder      : ident (COMMA ident)* IN expr ;

expr
    : primary                                                   # primaryExpr
    | expr DOT ident                                            # memberExpr
    | expr LPAREN argList? RPAREN                               # callExpr
    | expr LBRACK expr (COMMA expr)* RBRACK                     # indexExpr
    | <assoc=right> expr CARET expr                             # powExpr
    | MINUS expr                                                # negExpr
    | expr op=(STAR | SLASH | PERCENT) expr                     # mulExpr
    | expr op=(PLUS | MINUS) expr                               # addExpr
    | expr DOTDOT expr                                          # rangeExpr
    | expr op=(EQ | NEQ | LT | LE | GT | GE) expr                # cmpExpr
    | expr IN expr                                              # inExpr
    | NOT expr                                                  # notExpr
    | expr AND expr                                             # andExpr
    | expr OR expr                                              # orExpr
    | <assoc=right> expr ARROW_FAT expr                         # impliesExpr
    | expr IFF expr                                             # iffExpr
    | quant=(FORALL | EXISTS) binder (WHERE expr)? COLON expr   # quantExpr
    | IF expr THEN expr ELSE expr                               # ifExpr
    ;

primary
    : NUMBER                                                    # numberLit
    | STRING                                                    # stringLit
    | (TRUE | FALSE)                                            # boolLit
    | ident                                                     # nameRef
    | LPAREN expr (COMMA expr)* RPAREN                          # parenOrTuple
    | LBRACK (expr (COMMA expr)* COMMA?)? RBRACK                # listLit
    ;

argList     : arg (COMMA arg)* ;
arg         : (ident COLON)? expr ;

ident       : ID ;

// ---------------------------------------------------------------------------------------------
// Lexer. Keywords have named tokens so messages never show implicit token names.
// ---------------------------------------------------------------------------------------------

DOMAIN   : 'domain' ;
IMPORT   : 'import' ;
WORLD    : 'world' ;
SIMULATOR : 'simulator' ;
ROBOT    : 'robot' ;
CLEARANCE : 'clearance' ;
CONST    : 'const' ;
ENUM     : 'enum' ;
ITEMS    : 'items' ;
ITEM     : 'item' ;
OBSERVE  : 'observe' ;
FEEDBACK : 'feedback' ;
EXTERN   : 'extern' ;
FN       : 'fn' ;
SAMPLER  : 'sampler' ;
ACTION   : 'action' ;
VAR      : 'var' ;
REQUIRE  : 'require' ;
SAMPLE   : 'sample' ;
MINIMIZE : 'minimize' ;
MAXIMIZE : 'maximize' ;
PERSONAL : 'personal' ;
WHEN     : 'when' ;
MODEL    : 'model' ;
PER      : 'per' ;
ACCEPT   : 'accept' ;
FALLBACK : 'fallback' ;
EXPLORE  : 'explore' ;
LEARN    : 'learn' ;
GLOB     : 'glob' ;
REGEX    : 'regex' ;
SKILL    : 'skill' ;
DO       : 'do' ;
TASK     : 'task' ;
RUN      : 'run' ;
THEN     : 'then' ;
AS       : 'as' ;
FOR      : 'for' ;
IF       : 'if' ;
ELSE     : 'else' ;
ALLOW    : 'allow' ;
FORALL   : 'forall' ;
EXISTS   : 'exists' ;
WHERE    : 'where' ;
IN       : 'in' ;
AND      : 'and' ;
OR       : 'or' ;
NOT      : 'not' ;
TRUE     : 'true' ;
FALSE    : 'false' ;

ARROW     : '->' ;
ARROW_FAT : '=>' ;
IFF       : '<=>' ;
DOTDOT    : '..' ;
EQ        : '==' ;
NEQ       : '!=' ;
LE        : '<=' ;
GE        : '>=' ;
LT        : '<' ;
GT        : '>' ;
ASSIGN    : '=' ;
PLUS      : '+' ;
MINUS     : '-' ;
STAR      : '*' ;
SLASH     : '/' ;
PERCENT   : '%' ;
CARET     : '^' ;
TILDE     : '~' ;
DOT       : '.' ;
COMMA     : ',' ;
COLON     : ':' ;
SEMI      : ';' ;
LPAREN    : '(' ;
RPAREN    : ')' ;
LBRACK    : '[' ;
RBRACK    : ']' ;
LBRACE    : '{' ;
RBRACE    : '}' ;
UNDERSCORE : '_' ;

NUMBER   : DIGIT+ ('.' DIGIT+)? ([eE] [+-]? DIGIT+)? ;
ID       : [a-zA-Z_] [a-zA-Z_0-9]* ;
STRING   : '"' (~["\\\r\n] | '\\' ~[\r\n])* '"' ;

// Malformed input still becomes tokens, so the parser can report it with a location and a plain
// message instead of ANTLR's "token recognition error".
UNTERMINATED_STRING  : '"' (~["\\\r\n] | '\\' ~[\r\n])* ;
UNTERMINATED_COMMENT : '/*' ( ~'*' | '*'+ ~[*/] )* '*'* EOF ;

LINE_COMMENT  : '//' ~[\r\n]* -> channel(HIDDEN) ;
BLOCK_COMMENT : '/*' .*? '*/' -> channel(HIDDEN) ;
WS            : [ \t\r\n\f]+ -> channel(HIDDEN) ;

ERROR_CHAR : . ;

fragment DIGIT : [0-9] ;
